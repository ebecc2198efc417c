#pragma once
// What neopipe is measured against, in the same run: the OpenCV way to get blob centroids, and a
// memory-read floor (the cost of looking at every pixel once).

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>

namespace neopipe::bench {

/// cv::threshold (THRESH_BINARY) then cv::connectedComponentsWithStats (8-connected, CV_32S labels,
/// stats and centroids). Returns the number of components, background excluded.
class OpenCvBlobs {
 public:
  int operator()(const cv::Mat& gray, int threshold);

 private:
  cv::Mat binary_, labels_, stats_, centroids_;
};

/// One pass summing the frame's pixels, cut into row stripes over `threads` threads.
class ReadFloor {
 public:
  explicit ReadFloor(int threads);
  ~ReadFloor();
  ReadFloor(const ReadFloor&) = delete;
  ReadFloor& operator=(const ReadFloor&) = delete;
  std::uint64_t operator()(const cv::Mat& gray);

 private:
  struct Arena;  // defined in the .cpp to keep oneTBB out of this header
  int threads_;
  std::unique_ptr<Arena> arena_;
};

}  // namespace neopipe::bench
