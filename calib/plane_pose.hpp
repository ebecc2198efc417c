#pragma once
// Where the calibrated plane lies in the camera's frame, recovered from the full model: the
// homography from undistorted pixels to the plane is K [r1 r2 t] up to scale, so the intrinsics give
// the plane's axes and origin back. With them a pixel's viewing ray can meet any plane parallel to
// the calibrated one: the centre of a marble, one radius above the table, is not on the table, and
// the table is not where a calibration board of some thickness lay.

#include <Eigen/Core>
#include <vector>

#include "calib/calibration.hpp"

namespace neopipe::calib {

/// The calibrated plane in camera coordinates: a plane point (X, Y) and height Z above it (mm, Z
/// towards the camera) is at X * x_axis + Y * y_axis + Z * z_axis + origin.
struct PlanePose {
  Eigen::Vector3d x_axis = Eigen::Vector3d::UnitX();
  Eigen::Vector3d y_axis = Eigen::Vector3d::UnitY();
  Eigen::Vector3d z_axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

/// The plane's pose from a full-model calibration. Throws CalibrationError for the plane
/// homography (it has no camera to speak of) or a degenerate homography.
PlanePose plane_pose(const Calibration& calibration);

/// Plane coordinates (mm) of the points seen at `pixels` that lie `height` mm above the calibrated
/// plane (towards the camera; negative: below it). Height 0 gives Calibration::to_world. Throws
/// CalibrationError for the plane homography unless height is 0, and for a ray parallel to the plane.
std::vector<Eigen::Vector2d> to_world_at_height(const Calibration& calibration,
                                                const std::vector<Eigen::Vector2d>& pixels, double height);

/// Where points at plane coordinates `world` (mm), `height` mm above the calibrated plane, appear in
/// the image (px): the inverse of to_world_at_height. Throws as it does.
std::vector<Eigen::Vector2d> to_pixel_at_height(const Calibration& calibration,
                                                const std::vector<Eigen::Vector2d>& world, double height);

}  // namespace neopipe::calib
