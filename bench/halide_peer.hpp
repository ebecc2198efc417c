#pragma once
// The Halide composite `neopipe bench` measures the chain case against: the iconic stages (smooth,
// threshold, erode, dilate) compiled ahead of time from bench/halide/chain_generator.cpp, followed
// by neopipe's own blob stage (pipeline/striped_blobs.hpp) weighted by the source frame: what a
// user who wrote those stages in Halide and kept neopipe's blob extraction would run.
//
// Built when CMake finds Halide 14 (Debian's libhalide14-0-dev); otherwise halide_available() is
// false and constructing a HalideChain throws.

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "pipeline/value.hpp"

namespace neopipe::bench {

/// True when this build has the Halide peer.
bool halide_available();

class HalideChain {
 public:
  /// `threads`: Halide's thread pool and the blob stage's task arena both get this many.
  explicit HalideChain(int threads);
  ~HalideChain();
  HalideChain(const HalideChain&) = delete;
  HalideChain& operator=(const HalideChain&) = delete;

  /// The opened binary image of `gray` (CV_8UC1, at least 1 x 1): 255 or 0.
  cv::Mat iconic(const cv::Mat& gray, int threshold);
  /// The whole chain on one frame: its blob table.
  pipeline::BlobList operator()(const cv::Mat& gray, int threshold);

  /// The chain as a stream, as the executor runs graphs: submit frames one after another, then
  /// finish. With more than one thread the blob stage of frame i runs while Halide computes frame
  /// i + 1 (two binary images in flight); with one, each frame is done before submit returns.
  void submit(const cv::Mat& gray, int threshold);
  /// Waits for the last frame; returns the blobs found since the previous finish().
  std::int64_t finish();

 private:
  void iconic(const cv::Mat& gray, int threshold, cv::Mat& out);
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace neopipe::bench
