#pragma once
// Calibration targets as the global camera sees them: a grid of bright dots on a dark board, or a
// chessboard on white paper, at any pose in space, with the same lens, light, blur and noise as the
// marbles. Rendered by tracing each pixel corner back to the target's plane and area-sampling the
// pixels an edge crosses.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "sim/camera.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/scene_renderer.hpp"

namespace neopipe::sim {

enum class TargetKind { dots, chessboard };

struct CalibrationTarget {
  TargetKind kind = TargetKind::chessboard;
  int cols = 9;             ///< dots per row, or squares per row of a chessboard
  int rows = 6;             ///< dot rows, or squares per column
  double pitch = 20;        ///< mm between dot centres, or a square's side
  double dot_diameter = 8;  ///< mm (dots only)
};

/// Where the target lies: target point (s, t, 0) (mm, s along its rows, t along its columns, from
/// the first dot or the board's first inner corner) is at world rotation * (s, t, 0) + translation.
/// This is the printed face: a board of thickness h lying flat on the table has its face at z = h,
/// so its pose is target_pose(x, y, h, theta) (the board's edges are not drawn).
struct TargetPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

/// A pose from the plane's terms: the target's origin at (x, y, z) mm, turned theta degrees about
/// the vertical, then tipped tilt_x degrees about its own s axis and tilt_y about its t axis.
TargetPose target_pose(double x, double y, double z, double theta_deg, double tilt_x_deg = 0, double tilt_y_deg = 0);

/// The target's feature points in its own plane, row by row: dot centres, or a chessboard's inner
/// corners ((cols - 1) x (rows - 1), as cv::findChessboardCorners orders them for a board seen
/// upright).
std::vector<Eigen::Vector2d> target_points(const CalibrationTarget& target);

/// Those points projected into the image (px), in the same order.
std::vector<Eigen::Vector2d> projected_target_points(const CalibrationTarget& target, const TargetPose& pose,
                                                     const PinholeCamera& camera);

/// One 8-bit frame of the target on the workspace, exposed by `renderer` (its model and size).
cv::Mat render_target(const CalibrationTarget& target, const TargetPose& pose, const PinholeCamera& camera,
                      const MarbleRenderer& renderer, std::int64_t frame = 0);
/// The same under `renderer`'s Rendering: the printed face is matte (Lambertian, no highlight) under
/// the same light as the marbles, the table around it textured and lit, and the frame goes through
/// the same lens (the camera's), defocus, vignetting and sensor. The board casts no shadow. Under
/// ImageModel settings (the ideal preset), the MarbleRenderer overload's image exactly.
cv::Mat render_target(const CalibrationTarget& target, const TargetPose& pose, const PinholeCamera& camera,
                      const SceneRenderer& renderer, std::int64_t frame = 0);
/// The light (CV_32F gray levels) that overload exposes: before defocus, vignetting and noise.
cv::Mat target_light(const CalibrationTarget& target, const TargetPose& pose, const PinholeCamera& camera,
                     const SceneRenderer& renderer);

}  // namespace neopipe::sim
