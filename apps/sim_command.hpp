#pragma once
// `neopipe sim`: make worlds, render camera frames and videos, drive the arm.

#include <CLI/CLI.hpp>
#include <string>

#include "apps/sim_arm_command.hpp"

namespace neopipe::apps {

struct SimWorldArgs {
  int objects = 100;
  std::string size = "500x500";
  double diameter = 5.0;
  double min_gap = 3.0;
  std::uint64_t seed = 1;
  std::string out;
};

/// What `sim render` and `sim video` share: the world, the camera and the image model.
struct SimCameraArgs {
  std::string world;
  std::string camera = "global";
  std::string resolution = "1280x960";  ///< global camera
  double distance = 1000;               ///< global: mm from the workspace centre
  double tilt = 4;                      ///< global: degrees from vertical
  double tilt_azimuth = 30;             ///< global: direction of the lean, degrees from East
  double roll = 2;                      ///< global: degrees about the optical axis
  std::string distortion;               ///< k1,k2,p1,p2,k3; empty: the camera's default
  double window = 50;                   ///< onboard: view window side a, mm
  double noise = 2.0;
  double blur = 0.7;
  double gradient = 0.15;
  std::uint64_t seed = 1;
  std::string out;
  std::string truth;
};

struct SimRenderArgs {
  SimCameraArgs cam;
  std::string pose;  ///< onboard: x,y,theta (mm, mm, degrees); default the workspace centre
  std::string camera_out;
  std::string target;       ///< "", dots or chessboard
  std::string target_grid;  ///< CxR: dots, or squares of a chessboard
  double pitch = 20;        ///< mm
  double dot_diameter = 8;  ///< mm
  std::string target_pose;  ///< x,y,z,theta[,tilt_x,tilt_y]
};

struct SimVideoArgs {
  SimCameraArgs cam;
  std::string path;   ///< onboard: CSV x,y,theta
  int steps = 1;      ///< frames from one path row to the next
  int frames = 150;   ///< global: length of the clip
  double speed = 20;  ///< global: marble speed, mm/s
  double fps = 30;
  bool quiet = false;
};

struct SimArgs {
  SimWorldArgs world;
  SimRenderArgs render;
  SimVideoArgs video;
  SimArmArgs arm;
};

/// Declares `sim` and its subcommands on `parent`; returns `sim`.
CLI::App* add_sim_command(CLI::App& parent, SimArgs& args);
/// Runs whichever subcommand was given; returns the process exit code.
int sim_command(const CLI::App& sim, const SimArgs& args);

}  // namespace neopipe::apps
