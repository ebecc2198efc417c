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
  /// The summed areas of the last call's components.
  std::int64_t total_area() const;

 private:
  cv::Mat binary_, labels_, stats_, centroids_;
};

/// The chain case the OpenCV way: cv::GaussianBlur 3x3 (sigma 0: the kernel [1 2 1]/4 both ways,
/// computed in exact fixed point and rounded half up for 8-bit images, which is neopipe's smooth
/// preset bit for bit) with BORDER_REPLICATE (neopipe's default border), cv::threshold, a 3x3 opening
/// (cv::morphologyEx MORPH_OPEN, rectangle), cv::connectedComponentsWithStats as OpenCvBlobs does.
/// Returns the number of components, background excluded.
class OpenCvChain {
 public:
  OpenCvChain();
  int operator()(const cv::Mat& gray, int threshold);
  /// The summed areas of the last call's components.
  std::int64_t total_area() const;

 private:
  cv::Mat kernel_, smooth_, binary_, opened_, labels_, stats_, centroids_;
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
