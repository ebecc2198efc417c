#pragma once
// The two cameras of the rig: the global camera above the workspace (what the map-maker sees) and
// the onboard camera on the arm's end effector (what the navigator sees).

#include <Eigen/Core>
#include <array>
#include <opencv2/core/types.hpp>

#include "sim/camera.hpp"
#include "sim/pose2.hpp"

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

struct OnboardCameraConfig {
  int side_px = 256;      ///< square image, PIPE's frame size
  double window_mm = 50;  ///< side a of the view window on the plane
  double height = 100;    ///< mm above the plane (with no distortion only the ratio matters)
  std::array<double, 5> distortion{};
};

/// The onboard camera when the tool frame is at `pose`: looking straight down, the window centred
/// on the tool, image x along the tool's x axis, image up along its y axis.
PinholeCamera make_onboard_camera(const Pose2& pose, const OnboardCameraConfig& config = {});

}  // namespace neopipe::sim
