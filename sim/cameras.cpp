#include "sim/cameras.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace neopipe::sim {
namespace {

double radians(double deg) {
  return deg * std::numbers::pi / 180;
}

}  // namespace

PinholeCamera make_global_camera(const Eigen::Vector2d& workspace, const GlobalCameraConfig& c) {
  const Eigen::Vector3d look(workspace.x() / 2, workspace.y() / 2, 0);
  const double tilt = radians(c.tilt_deg);
  const double az = radians(c.tilt_azimuth_deg);
  const Eigen::Vector3d centre =
      look + c.distance * Eigen::Vector3d(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
  // Image down is South as seen from above, so North is up in the image, turned by the roll.
  const Eigen::Vector3d z = (look - centre).normalized();
  const Eigen::Vector3d south(0, -1, 0);
  const Eigen::Vector3d y0 = (south - south.dot(z) * z).normalized();
  const Eigen::Vector3d x0 = y0.cross(z);
  const double roll = radians(c.roll_deg);
  const Eigen::Vector3d x = std::cos(roll) * x0 + std::sin(roll) * y0;
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = y.transpose();
  r.row(2) = z.transpose();
  const Eigen::Vector3d t = -r * centre;

  // Fit the focal length: the workspace corners' undistorted directions at f = 1, scaled so the
  // widest one lands on the margin.
  Intrinsics k;
  k.size = c.resolution;
  k.cx = (c.resolution.width - 1) / 2.0;
  k.cy = (c.resolution.height - 1) / 2.0;
  double needed = 0;
  for (const double wx : {0.0, workspace.x()}) {
    for (const double wy : {0.0, workspace.y()}) {
      const Eigen::Vector3d p = r * Eigen::Vector3d(wx, wy, 0) + t;
      needed = std::max(needed, std::abs(p.x() / p.z()) / (k.cx + 0.5));
      needed = std::max(needed, std::abs(p.y() / p.z()) / (k.cy + 0.5));
    }
  }
  k.fx = k.fy = (1 - c.margin) / needed;
  k.distortion = c.distortion;
  return {k, r, t};
}

PinholeCamera make_global_camera(const Eigen::Vector2d& workspace, const GlobalCameraConfig& config,
                                 const Rendering& rendering) {
  GlobalCameraConfig c = config;
  c.distortion = rendering.lens.opencv;
  const PinholeCamera camera = make_global_camera(workspace, c);
  Intrinsics k = camera.intrinsics();
  k.extra = rendering.lens.extra;
  check_lens_unfolded(k);
  return {k, camera.rotation(), camera.translation()};
}

PinholeCamera make_onboard_camera(const Pose2& pose, const OnboardCameraConfig& c) {
  Intrinsics k;
  k.size = {c.side_px, c.side_px};
  k.fx = k.fy = c.side_px / c.window_mm * c.height;
  k.cx = k.cy = (c.side_px - 1) / 2.0;
  k.distortion = c.distortion;
  return PinholeCamera::looking_down(k, pose, c.window_plane_z + c.height);
}

PinholeCamera make_onboard_camera(const Pose2& pose, const OnboardCameraConfig& config, const Rendering& rendering) {
  return onboard_camera_at(pose, config, onboard_intrinsics(config, rendering));
}

Intrinsics onboard_intrinsics(const OnboardCameraConfig& config, const Rendering& rendering) {
  OnboardCameraConfig c = config;
  c.distortion = rendering.lens.opencv;
  Intrinsics k = make_onboard_camera({}, c).intrinsics();
  k.extra = rendering.lens.extra;
  check_lens_unfolded(k);
  return k;
}

PinholeCamera onboard_camera_at(const Pose2& pose, const OnboardCameraConfig& config, const Intrinsics& intrinsics) {
  return PinholeCamera::looking_down(intrinsics, pose, config.window_plane_z + config.height);
}

void check_lens_unfolded(const Intrinsics& k) {
  // The corners' normalised radius as if undistorted, with a margin for barrel distortion pushing
  // the scene's corners further out than the image's.
  double field = 0;
  for (const double u : {-0.5, k.size.width - 0.5}) {
    for (const double v : {-0.5, k.size.height - 0.5})
      field = std::max(field, std::hypot((u - k.cx) / k.fx, (v - k.cy) / k.fy));
  }
  field *= 1.25;
  if (const auto fold = lens_fold_radius(k.lens(), field)) {
    throw std::invalid_argument(fmt::format(
        "lens: the distortion folds the image at normalised radius {:.3f}, inside its corners ({:.3f} with a margin)",
        *fold, field));
  }
}

}  // namespace neopipe::sim
