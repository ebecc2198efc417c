#pragma once
// Runs a compiled graph on a stream of frames, PIPE-style: several frames in flight at once, each
// node busy on a different frame (stateful nodes run frames in order, one at a time; stateless ones
// may overlap frames), chains of point and 3x3 nodes fused into stripe-by-stripe steps, and stripes
// of rows run in parallel. Results come back in frame order and are identical for every thread
// count: the kernels are row-independent and every reduction is exact.
//
// Threading: one driver thread (the caller: it submits frames and consumes results; run_stream
// reads them on a reader thread of its own) plus `threads` oneTBB workers in the executor's arena.

#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline {

struct ExecutorOptions {
  int threads = 0;            ///< worker threads; 0 = one per hardware thread
  /// Frames being processed at once (>= 2); 0 = 2 * (threads + 2): a blocked submit waits for half
  /// the slots to free and refills them in one go, while the other half keep every worker busy.
  int frames_in_flight = 0;
  int min_stripe_rows = 16;   ///< stripes are never shorter than this
  bool fuse = true;           ///< run chains of point and 3x3 nodes as fused steps (see fusion.hpp)
  int fused_stripe_rows = 0;  ///< rows per stripe of a fused step; 0 = sized to the cache
};

struct FrameResult {
  std::int64_t index = 0;      ///< the index the frame was submitted with
  cv::Mat input;               ///< the frame as submitted
  std::vector<Value> outputs;  ///< the graph's outputs, in declaration order
  double latency_s = 0;        ///< submit to completion
};

class Executor {
 public:
  using ResultHandler = std::function<void(FrameResult&&)>;

  /// Results are delivered, in submission order, to `on_result` on the driver thread (inside
  /// submit, try_submit, poll and finish).
  Executor(CompiledGraph graph, ExecutorOptions options, ResultHandler on_result);
  ~Executor();
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  /// Submits a frame (CV_8UC3 for a bgr8 source, CV_8UC1 for gray8), blocking while the pipeline is
  /// full. All frames must have the first frame's size. A delayed edge delivers the value from the
  /// previously submitted frame. Throws the first processing error, after delivering every result
  /// that finished before it; throws std::invalid_argument for a frame of the wrong type or size.
  void submit(std::int64_t index, const cv::Mat& frame);
  /// Like submit, but returns false at once (frame not taken) when the pipeline is full.
  bool try_submit(std::int64_t index, const cv::Mat& frame);
  /// Delivers finished results without waiting.
  void poll();
  /// Waits for every submitted frame and delivers the remaining results; rethrows as submit does.
  void finish();

  const CompiledGraph& graph() const;
  int threads() const;
  int frames_in_flight() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience for tests and tools: runs `frames` (indices 0, 1, ...) and returns the results.
std::vector<FrameResult> run_frames(CompiledGraph graph, const std::vector<cv::Mat>& frames,
                                    ExecutorOptions options = {});

}  // namespace neopipe::pipeline
