#pragma once
// A pinhole camera with OpenCV's lens distortion model (k1, k2, p1, p2, k3), looking at the
// workspace plane z = 0 (world x East, y North, z up, millimetres). The same model as
// cv::projectPoints, so calibration can be checked against the truth it was rendered from; with
// LensExtras (sim/lens.hpp) it is a lens that model cannot fit exactly.

#include <Eigen/Core>
#include <array>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "sim/lens.hpp"
#include "sim/pose2.hpp"

namespace neopipe::sim {

struct Intrinsics {
  double fx = 1000;
  double fy = 1000;
  double cx = 639.5;  ///< pixel centres at integer coordinates, as OpenCV
  double cy = 479.5;
  std::array<double, 5> distortion{};  ///< k1, k2, p1, p2, k3
  cv::Size size{1280, 960};
  LensExtras extra{};  ///< terms beyond OpenCV's five (none: exactly OpenCV's model)

  [[nodiscard]] Lens lens() const { return {distortion, extra}; }
  bool operator==(const Intrinsics&) const = default;
};

class PinholeCamera {
 public:
  /// `rotation` and `translation` map world to camera coordinates: Xc = R Xw + t; the camera looks
  /// along its +z, image x to the right, image y down.
  PinholeCamera(Intrinsics intrinsics, Eigen::Matrix3d rotation, Eigen::Vector3d translation);

  /// A camera `height` mm above the plane looking straight down, centred on `pose`, image x along the
  /// pose's x axis and image up along its y axis.
  static PinholeCamera looking_down(const Intrinsics& intrinsics, const Pose2& pose, double height);

  /// Pixel position of a world point, or nothing if it lies behind (or on) the camera plane.
  [[nodiscard]] std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& world) const;
  /// d(u, v) / d(x, y) at a point of the plane z = 0: how a small disk there maps into the image.
  [[nodiscard]] Eigen::Matrix2d plane_jacobian(const Eigen::Vector2d& on_plane) const;
  /// The point of the plane z = 0 seen at pixel (u, v) (lens distortion inverted), or nothing if that
  /// ray does not meet the plane in front of the camera.
  [[nodiscard]] std::optional<Eigen::Vector2d> plane_point(const Eigen::Vector2d& pixel) const;
  /// The same for the plane z = h: (x, y) of the point at that height seen at the pixel.
  [[nodiscard]] std::optional<Eigen::Vector2d> plane_point(const Eigen::Vector2d& pixel, double h) const;
  /// The camera's centre in world coordinates.
  [[nodiscard]] Eigen::Vector3d centre() const { return -r_.transpose() * t_; }
  /// Normalised undistorted coordinates (x/z, y/z) of the ray through a pixel.
  [[nodiscard]] Eigen::Vector2d undistort(const Eigen::Vector2d& pixel) const;
  /// Applies the lens model to normalised coordinates and returns the pixel.
  [[nodiscard]] Eigen::Vector2d distort_to_pixel(const Eigen::Vector2d& normalised) const;

  [[nodiscard]] const Intrinsics& intrinsics() const { return k_; }
  [[nodiscard]] const Eigen::Matrix3d& rotation() const { return r_; }
  [[nodiscard]] const Eigen::Vector3d& translation() const { return t_; }
  [[nodiscard]] cv::Size size() const { return k_.size; }
  /// OpenCV's 3x3 camera matrix and 1x5 distortion coefficients (CV_64F).
  [[nodiscard]] cv::Mat camera_matrix() const;
  [[nodiscard]] cv::Mat distortion_coefficients() const;
  /// The terms beyond those five, 1x5 CV_64F: k4, s1, s2, s3, s4 (sim/lens.hpp).
  [[nodiscard]] cv::Mat extra_distortion_coefficients() const;

 private:
  Intrinsics k_;
  Eigen::Matrix3d r_;
  Eigen::Vector3d t_;
};

}  // namespace neopipe::sim
