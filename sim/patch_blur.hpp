#pragma once
// Gaussian blur of small float patches with zeros around them (a marble's light before the lens
// spreads it). cv::GaussianBlur spends more on building its kernel and filter objects than on a
// 35x35 patch, thousands of times a second; this keeps the kernel and does the two passes plainly.

#include <opencv2/core/mat.hpp>
#include <vector>

namespace neopipe::sim {

class PatchBlur {
 public:
  /// sigma > 0 px; the kernel reaches ceil(4 sigma) pixels each way.
  explicit PatchBlur(double sigma);
  /// Blurs `patch` (CV_32F) in place, as if the image beyond it were 0 (cv::BORDER_CONSTANT).
  void apply(cv::Mat& patch) const;
  [[nodiscard]] int radius() const { return radius_; }
  /// The normalised 1-D kernel, 2 radius + 1 taps.
  [[nodiscard]] const std::vector<float>& kernel() const { return kernel_; }

 private:
  int radius_;
  std::vector<float> kernel_;
};

}  // namespace neopipe::sim
