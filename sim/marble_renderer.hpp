#pragma once
// Renders marbles on the workspace as a camera sees them: each marble's disk is mapped into the
// image through the camera's local (affine) map at its centre, its pixels are area-sampled where
// the rim crosses them, so the blob's centroid is the projected centre to a small fraction of a
// pixel. Then illumination, blur and noise as the ImageModel says.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <span>
#include <vector>

#include "sim/camera.hpp"
#include "sim/gaussian_noise.hpp"
#include "sim/image_model.hpp"
#include "sim/patch_blur.hpp"

namespace neopipe::sim {

/// Where a marble's centre lands in the image.
struct ProjectedMarble {
  int id = 0;
  double u = 0;
  double v = 0;
};

class MarbleRenderer {
 public:
  /// Precomputes what does not change from frame to frame for images of `size`.
  MarbleRenderer(const ImageModel& model, cv::Size size);

  /// One 8-bit gray frame of the marbles centred at `centres` (mm, on the plane), seen by `camera`
  /// (whose size must be this renderer's). `frame` selects the noise.
  [[nodiscard]] cv::Mat render(std::span<const Eigen::Vector2d> centres, double diameter, const PinholeCamera& camera,
                               std::int64_t frame) const;

  /// Any scene's light (CV_32F gray levels before illumination, this renderer's size) through the
  /// same blur, illumination and noise: how calibration targets are exposed.
  [[nodiscard]] cv::Mat expose(const cv::Mat& light, std::int64_t frame) const;

  [[nodiscard]] const ImageModel& model() const { return model_; }

 private:
  void splat(const Eigen::Vector2d& centre, double radius, const PinholeCamera& camera, cv::Mat& excess) const;
  [[nodiscard]] cv::Mat finish(const cv::Mat& excess, std::int64_t frame) const;

  ImageModel model_;
  cv::Size size_;
  cv::Mat gain_;  ///< CV_32F illumination factor per pixel
  GaussianNoise noise_;
  std::optional<PatchBlur> blur_;
};

/// The fraction of a unit pixel on the inner side of a straight edge passing at signed distance `s`
/// (px, positive when the pixel's centre is inside) with unit normal (nx, ny): exact box filtering.
double pixel_coverage(double s, double nx, double ny);

/// The marbles whose centres project strictly inside the image, in id order.
std::vector<ProjectedMarble> visible_marbles(std::span<const Eigen::Vector2d> centres, const PinholeCamera& camera);

}  // namespace neopipe::sim
