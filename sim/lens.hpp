#pragma once
// The lens: OpenCV's five-term distortion (k1, k2, p1, p2, k3) plus terms that model cannot
// represent, so a calibration with OpenCV's model leaves a residual as it does on a real lens: a
// polynomial radial term k4 r^8 (OpenCV's own k4 is a term of a rational model, not this) and
// thin-prism distortion s1..s4 (as OpenCV defines them; its five-term model has no such terms).
// On normalised undistorted coordinates (x, y), r^2 = x^2 + y^2:
//   x' = x (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8) + 2 p1 x y + p2 (r^2 + 2 x^2) + s1 r^2 + s2 r^4
//   y' = y (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8) + p1 (r^2 + 2 y^2) + 2 p2 x y + s3 r^2 + s4 r^4

#include <Eigen/Core>
#include <array>
#include <optional>

namespace neopipe::sim {

/// The terms beyond OpenCV's five; all zero is OpenCV's model exactly.
struct LensExtras {
  double k4 = 0;  ///< radial, times r^8
  double s1 = 0;  ///< thin prism: x' += s1 r^2 + s2 r^4
  double s2 = 0;
  double s3 = 0;  ///< thin prism: y' += s3 r^2 + s4 r^4
  double s4 = 0;

  [[nodiscard]] bool any() const { return k4 != 0 || s1 != 0 || s2 != 0 || s3 != 0 || s4 != 0; }
  [[nodiscard]] std::array<double, 5> as_array() const { return {k4, s1, s2, s3, s4}; }
  static LensExtras from_array(const std::array<double, 5>& a) { return {a[0], a[1], a[2], a[3], a[4]}; }
  bool operator==(const LensExtras&) const = default;
};

struct Lens {
  std::array<double, 5> opencv{};  ///< k1, k2, p1, p2, k3
  LensExtras extra{};
  bool operator==(const Lens&) const = default;
};

/// The distorted normalised coordinates of undistorted `n`.
[[nodiscard]] Eigen::Vector2d distort(const Lens& lens, const Eigen::Vector2d& n);
/// d distort / d n at `n`.
[[nodiscard]] Eigen::Matrix2d distortion_jacobian(const Lens& lens, const Eigen::Vector2d& n);
/// The undistorted coordinates whose distortion is `distorted`, by Newton's method from `start`
/// (a neighbour's answer converges in one or two steps), until a step is below `tolerance`.
[[nodiscard]] Eigen::Vector2d undistort(const Lens& lens, const Eigen::Vector2d& distorted,
                                        const Eigen::Vector2d& start, double tolerance = 1e-15);

/// The smallest normalised radius up to `field` at which the lens folds the image (the map stops
/// being one-to-one: its Jacobian's determinant, or the growth of the distorted radius along a
/// ray from the centre, is no longer positive), or nothing if it does not fold within `field`.
[[nodiscard]] std::optional<double> lens_fold_radius(const Lens& lens, double field);

}  // namespace neopipe::sim
