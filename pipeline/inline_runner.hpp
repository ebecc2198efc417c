#pragma once
// Runs a compiled graph on one frame at a time, on the calling thread, and hands back that frame's
// outputs before the next frame exists. For callers that must see each result before they can
// decide what to look at next (a navigator's eye: look, move, look again), where the executor's
// frames in flight and worker threads would only add latency and a process-wide thread limit.
//
// Every node runs whole-frame, in the compiled order, exactly as the executor runs a lone frame, so
// the outputs are the executor's (tested). Delay edges read the previous call's value (the declared
// initial value on the first call), as they do in a stream.

#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline {

class InlineRunner {
 public:
  explicit InlineRunner(CompiledGraph graph);

  /// Processes `frame` (CV_8UC3 for a bgr8 source, CV_8UC1 for gray8; every frame of the first's
  /// size) and returns the graph's outputs in declaration order. The values stay valid until the next
  /// call, which reuses their memory. Throws std::invalid_argument for a frame of the wrong type or
  /// size, GraphError when a node cannot run at the frame's size.
  const std::vector<Value>& run(const cv::Mat& frame);

  /// The output `index` of the last run (declaration order).
  [[nodiscard]] const Value& output(std::size_t index) const { return outputs_.at(index); }
  [[nodiscard]] const CompiledGraph& graph() const { return graph_; }
  /// Frames run so far.
  [[nodiscard]] std::int64_t frames() const { return frames_; }

 private:
  void configure(cv::Size size);
  const Value* input_value(std::size_t node, std::size_t input) const;

  CompiledGraph graph_;
  std::vector<std::vector<Value>> values_;    // [node][output port], reused from frame to frame
  std::vector<std::vector<Value>> previous_;  // [node][input]: a delayed input's value for this frame
  std::vector<Value> outputs_;
  cv::Size size_;
  std::int64_t frames_ = 0;
};

}  // namespace neopipe::pipeline
