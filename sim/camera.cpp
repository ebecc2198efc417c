#include "sim/camera.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

namespace neopipe::sim {

PinholeCamera::PinholeCamera(Intrinsics intrinsics, Eigen::Matrix3d rotation, Eigen::Vector3d translation)
    : k_(intrinsics), r_(std::move(rotation)), t_(std::move(translation)) {}

PinholeCamera PinholeCamera::looking_down(const Intrinsics& intrinsics, const Pose2& pose, double height) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  Eigen::Matrix3d r;     // rows: the camera's axes in world coordinates
  r.row(0) << c, s, 0;   // image x: the tool's x axis
  r.row(1) << s, -c, 0;  // image y (down): minus the tool's y axis
  r.row(2) << 0, 0, -1;  // optical axis: straight down
  const Eigen::Vector3d centre(pose.x, pose.y, height);
  return {intrinsics, r, -r * centre};
}

Eigen::Vector2d PinholeCamera::distort_to_pixel(const Eigen::Vector2d& n) const {
  if (k_.extra.any()) {
    const Eigen::Vector2d d = distort(k_.lens(), n);
    return {k_.fx * d.x() + k_.cx, k_.fy * d.y() + k_.cy};
  }
  // OpenCV's model alone, in the arithmetic these images have always been made with.
  const auto& d = k_.distortion;
  const double x = n.x();
  const double y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  const double xd = x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x);
  const double yd = y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y;
  return {k_.fx * xd + k_.cx, k_.fy * yd + k_.cy};
}

std::optional<Eigen::Vector2d> PinholeCamera::project(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d c = r_ * world + t_;
  if (c.z() <= 0) return std::nullopt;
  return distort_to_pixel({c.x() / c.z(), c.y() / c.z()});
}

Eigen::Matrix2d PinholeCamera::plane_jacobian(const Eigen::Vector2d& p) const {
  // Central differences over 1 µm: the map is smooth at that scale, and truncation error (~h^2)
  // stays far below what rendering can resolve.
  constexpr double h = 1e-3;
  Eigen::Matrix2d j;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Vector3d plus(p.x(), p.y(), 0);
    Eigen::Vector3d minus = plus;
    plus[axis] += h;
    minus[axis] -= h;
    const auto a = project(plus);
    const auto b = project(minus);
    j.col(axis) = (a && b) ? Eigen::Vector2d((*a - *b) / (2 * h)) : Eigen::Vector2d::Zero();
  }
  return j;
}

Eigen::Vector2d PinholeCamera::undistort(const Eigen::Vector2d& pixel) const {
  Eigen::Vector2d target((pixel.x() - k_.cx) / k_.fx, (pixel.y() - k_.cy) / k_.fy);
  const auto& d = k_.distortion;
  if (k_.extra.any()) return sim::undistort(k_.lens(), target, target);
  if (d[0] == 0 && d[1] == 0 && d[2] == 0 && d[3] == 0 && d[4] == 0) return target;
  // Newton on distort(n) = target, with a numeric Jacobian: converges in a few steps for the mild
  // distortions cameras have, where OpenCV's fixed-point iteration needs more.
  Eigen::Vector2d n = target;
  auto distorted = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector2d px = distort_to_pixel(q);
    return Eigen::Vector2d((px.x() - k_.cx) / k_.fx, (px.y() - k_.cy) / k_.fy);
  };
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d f = distorted(n) - target;
    if (f.norm() < 1e-14) break;
    constexpr double h = 1e-7;
    Eigen::Matrix2d j;
    j.col(0) = (distorted(n + Eigen::Vector2d(h, 0)) - distorted(n - Eigen::Vector2d(h, 0))) / (2 * h);
    j.col(1) = (distorted(n + Eigen::Vector2d(0, h)) - distorted(n - Eigen::Vector2d(0, h))) / (2 * h);
    n -= j.partialPivLu().solve(f);
  }
  return n;
}

std::optional<Eigen::Vector2d> PinholeCamera::plane_point(const Eigen::Vector2d& pixel) const {
  return plane_point(pixel, 0.0);
}

std::optional<Eigen::Vector2d> PinholeCamera::plane_point(const Eigen::Vector2d& pixel, double h) const {
  const Eigen::Vector2d n = undistort(pixel);
  // Ray X = C + s R^T (n, 1); C = -R^T t. Meet z = h.
  const Eigen::Vector3d centre = -r_.transpose() * t_;
  const Eigen::Vector3d dir = r_.transpose() * Eigen::Vector3d(n.x(), n.y(), 1);
  if (std::abs(dir.z()) < 1e-15) return std::nullopt;
  const double s = (h - centre.z()) / dir.z();
  if (s <= 0) return std::nullopt;
  const Eigen::Vector3d x = centre + s * dir;
  return Eigen::Vector2d(x.x(), x.y());
}

cv::Mat PinholeCamera::camera_matrix() const {
  cv::Mat m = (cv::Mat_<double>(3, 3) << k_.fx, 0, k_.cx, 0, k_.fy, k_.cy, 0, 0, 1);
  return m;
}

cv::Mat PinholeCamera::distortion_coefficients() const {
  const auto& d = k_.distortion;
  cv::Mat m = (cv::Mat_<double>(1, 5) << d[0], d[1], d[2], d[3], d[4]);
  return m;
}

cv::Mat PinholeCamera::extra_distortion_coefficients() const {
  const auto& e = k_.extra;
  cv::Mat m = (cv::Mat_<double>(1, 5) << e.k4, e.s1, e.s2, e.s3, e.s4);
  return m;
}

}  // namespace neopipe::sim
