#pragma once
// Defocus that grows towards the image corners: a Gaussian blur whose sigma goes from
// Defocus::centre at the image centre to Defocus::corner at the corners, as the square of the
// distance from the centre (a lens focused on the centre of a flat field; the blur spot's radius
// grows about quadratically with the field angle). Marble patches are blurred with the sigma at
// their centre (a patch is a few pixels, where sigma hardly changes); whole frames (calibration
// targets) by blending the frame blurred at a few sigmas, per pixel, by that pixel's sigma.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "sim/patch_blur.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

class DefocusBlur {
 public:
  DefocusBlur(const Defocus& defocus, cv::Size size);

  /// The sigma (px) at image point (u, v).
  [[nodiscard]] double sigma(double u, double v) const;
  /// Blurs a patch (CV_32F, zeros beyond it) with the sigma at (u, v): the nearest of a bank of
  /// kernels 0.02 px apart.
  void blur_patch(cv::Mat& patch, double u, double v) const;
  /// How far (px) a patch's blur reaches: the widest kernel's radius.
  [[nodiscard]] int reach() const;
  /// The whole frame (CV_32F), borders replicated.
  [[nodiscard]] cv::Mat blur_frame(const cv::Mat& frame) const;

 private:
  Defocus defocus_;
  cv::Size size_;
  double half_diagonal2_;
  double step_ = 0.02;           // px of sigma between the bank's blurs
  std::vector<PatchBlur> bank_;  // sigmas centre, centre + step, ... corner; empty for no blur
};

}  // namespace neopipe::sim
