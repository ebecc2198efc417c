#include "calib/plane_pose.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <opencv2/calib3d.hpp>

namespace neopipe::calib {
namespace {

Eigen::Matrix3d to_eigen(const cv::Mat& m) {
  Eigen::Matrix3d e;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) e(i, j) = m.at<double>(i, j);
  }
  return e;
}

}  // namespace

PlanePose plane_pose(const Calibration& c) {
  if (c.model != Model::full || c.camera_matrix.empty()) {
    throw CalibrationError("the plane homography has no camera model: points off the plane need the full model");
  }
  const Eigen::Matrix3d k = to_eigen(c.camera_matrix);
  // world -> undistorted pixel is K [r1 r2 t] up to scale.
  const Eigen::Matrix3d m = k.inverse() * c.image_to_world.inverse();
  const double n1 = m.col(0).norm();
  const double n2 = m.col(1).norm();
  if (!(n1 > 0) || !(n2 > 0) || !std::isfinite(n1 + n2)) throw CalibrationError("degenerate plane homography");
  // A fitted homography's columns are not exactly orthonormal: take the mean scale.
  double scale = 2 / (n1 + n2);
  // The plane lies in front of the camera: its origin at positive camera depth.
  if (m(2, 2) * scale < 0) scale = -scale;
  PlanePose p;
  p.x_axis = scale * m.col(0);
  p.y_axis = scale * m.col(1);
  p.origin = scale * m.col(2);
  p.z_axis = p.x_axis.cross(p.y_axis).normalized() * (0.5 * (p.x_axis.norm() + p.y_axis.norm()));
  // Heights count towards the camera: the camera's centre (the origin of camera coordinates) must
  // lie on the positive side. A plane frame of the other handedness turns z the other way.
  if (p.z_axis.dot(-p.origin) < 0) p.z_axis = -p.z_axis;
  return p;
}

std::vector<Eigen::Vector2d> to_world_at_height(const Calibration& c, const std::vector<Eigen::Vector2d>& pixels,
                                                double height) {
  if (height == 0) return c.to_world(pixels);
  const PlanePose pose = plane_pose(c);
  std::vector<Eigen::Vector2d> out;
  out.reserve(pixels.size());
  if (pixels.empty()) return out;
  std::vector<cv::Point2d> in;
  in.reserve(pixels.size());
  for (const auto& p : pixels) in.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> rays;  // normalised, undistorted
  cv::undistortPoints(in, rays, c.camera_matrix, c.distortion_coefficients, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-12));
  const Eigen::Vector3d lifted = pose.origin + height * pose.z_axis;
  for (const auto& r : rays) {
    // X x_axis + Y y_axis - s ray = -lifted: the ray through the pixel meets the lifted plane.
    Eigen::Matrix3d a;
    a.col(0) = pose.x_axis;
    a.col(1) = pose.y_axis;
    a.col(2) = -Eigen::Vector3d(r.x, r.y, 1);
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
    if (!lu.isInvertible()) throw CalibrationError("a viewing ray runs parallel to the calibrated plane");
    const Eigen::Vector3d x = lu.solve(-lifted);
    out.emplace_back(x.x(), x.y());
  }
  return out;
}

std::vector<Eigen::Vector2d> to_pixel_at_height(const Calibration& c, const std::vector<Eigen::Vector2d>& world,
                                                double height) {
  if (height == 0) return c.to_pixel(world);
  const PlanePose pose = plane_pose(c);
  std::vector<Eigen::Vector2d> out;
  out.reserve(world.size());
  if (world.empty()) return out;
  std::vector<cv::Point3d> points;  // camera coordinates
  points.reserve(world.size());
  for (const auto& w : world) {
    const Eigen::Vector3d x = w.x() * pose.x_axis + w.y() * pose.y_axis + height * pose.z_axis + pose.origin;
    points.emplace_back(x.x(), x.y(), x.z());
  }
  std::vector<cv::Point2d> px;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), c.camera_matrix, c.distortion_coefficients, px);
  for (const auto& p : px) out.emplace_back(p.x, p.y);
  return out;
}

}  // namespace neopipe::calib
