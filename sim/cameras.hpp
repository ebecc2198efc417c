#pragma once
// The two cameras of the rig: the global camera above the workspace (what the map-maker sees) and
// the onboard camera on the arm's end effector (what the navigator sees).

#include <Eigen/Core>
#include <array>
#include <opencv2/core/types.hpp>

#include "sim/camera.hpp"
#include "sim/pose2.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

struct GlobalCameraConfig {
  cv::Size resolution{1280, 960};
  double distance = 1000;        ///< mm from the workspace centre to the camera
  double tilt_deg = 4;           ///< optical axis away from vertical: the image->plane map is projective
  double tilt_azimuth_deg = 30;  ///< direction (from East, counter-clockwise) the camera leans towards
  double roll_deg = 2;           ///< turn of the image about the optical axis
  double margin = 0.04;          ///< fraction of the image left around the workspace
  std::array<double, 5> distortion{-0.06, 0.015, 0.0004, -0.0003, 0};  ///< mild barrel, slight decentring
};

/// A camera that sees the whole W x H workspace: placed by `config`, focal length fitted so the
/// workspace fills the image but for the margin.
PinholeCamera make_global_camera(const Eigen::Vector2d& workspace, const GlobalCameraConfig& config = {});
/// The same camera with `rendering`'s lens (its OpenCV terms replace config.distortion, and its
/// extra terms). Throws std::invalid_argument if that lens folds the image inside its corners.
PinholeCamera make_global_camera(const Eigen::Vector2d& workspace, const GlobalCameraConfig& config,
                                 const Rendering& rendering);

struct OnboardCameraConfig {
  int side_px = 256;      ///< square image, PIPE's frame size
  double window_mm = 50;  ///< side a of the view window on the plane
  double height = 100;    ///< mm above the plane (with no distortion only the ratio matters)
  std::array<double, 5> distortion{};
  /// Height of the plane the window of side a lies in (the camera is `height` above it). The
  /// navigator's model of its camera says the image shows exactly that window; calibrated on its
  /// marbles it knows the window where the marbles' outlines are, at their centres' height: d / 2
  /// for spheres (onboard_config_for in sim/realism.hpp), 0 for today's flat disks.
  double window_plane_z = 0;
};

/// The onboard camera when the tool frame is at `pose`: looking straight down, the window centred
/// on the tool, image x along the tool's x axis, image up along its y axis.
PinholeCamera make_onboard_camera(const Pose2& pose, const OnboardCameraConfig& config = {});
/// The same camera with `rendering`'s lens (replacing config.distortion). Throws
/// std::invalid_argument if that lens folds the image inside its corners. Checking the lens takes
/// tens of microseconds: for a camera that moves frame by frame, make its intrinsics once with
/// onboard_intrinsics and place them with onboard_camera_at.
PinholeCamera make_onboard_camera(const Pose2& pose, const OnboardCameraConfig& config, const Rendering& rendering);
/// The onboard camera's intrinsics with `rendering`'s lens, checked as make_onboard_camera does.
Intrinsics onboard_intrinsics(const OnboardCameraConfig& config, const Rendering& rendering);
/// The onboard camera with `intrinsics` (from onboard_intrinsics) at `pose`.
PinholeCamera onboard_camera_at(const Pose2& pose, const OnboardCameraConfig& config, const Intrinsics& intrinsics);

/// Throws std::invalid_argument ("lens: ...") if `intrinsics`' lens folds the image inside its corners.
void check_lens_unfolded(const Intrinsics& intrinsics);

}  // namespace neopipe::sim
