#pragma once
// `neopipe sim`: make worlds, render camera frames and videos, drive the arm.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/sim_arm_command.hpp"
#include "apps/sim_panorama_command.hpp"

namespace neopipe::apps {

struct SimWorldArgs {
  int objects = 100;
  std::string size = "500x500";
  double diameter = 5.0;
  double min_gap = 3.0;
  std::uint64_t seed = 1;
  std::string out;
};

/// What `sim render` and `sim video` share: the world, the camera and how it renders (a realism
/// preset, each effect overridable; unset optionals keep the preset's value).
struct SimCameraArgs {
  std::string world;
  std::string camera = "global";
  std::string resolution = "1280x960";  ///< global camera
  double distance = 1000;               ///< global: mm from the workspace centre
  double tilt = 4;                      ///< global: degrees from vertical
  double tilt_azimuth = 30;             ///< global: direction of the lean, degrees from East
  double roll = 2;                      ///< global: degrees about the optical axis
  std::string distortion;               ///< k1,k2,p1,p2,k3; empty: the preset's
  std::string lens_extra;               ///< k4,s1,s2,s3,s4; empty: the preset's
  double window = 50;                   ///< onboard: view window side a, mm
  std::string realism = "rig";
  std::string light;  ///< x,y,z mm; empty: the preset's
  bool no_light = false;
  std::optional<double> ambient;
  std::optional<double> specular;
  std::optional<double> shininess;
  bool no_shadows = false;
  std::optional<double> texture;
  std::optional<double> vignetting;
  std::optional<double> noise;  ///< read noise sigma
  std::optional<double> full_well;
  bool no_shot_noise = false;
  std::optional<double> prnu;
  std::optional<double> blur;     ///< defocus sigma at the image centre
  std::optional<double> defocus;  ///< at the corners
  std::optional<double> gradient;
  bool interlace = false;
  bool no_interlace = false;
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
  std::string codec;           ///< none or jpeg; empty: the preset's
  std::optional<int> quality;  ///< jpeg quality 1..100; unset: the preset's
  bool quiet = false;
};

struct SimArgs {
  SimWorldArgs world;
  SimRenderArgs render;
  SimVideoArgs video;
  SimArmArgs arm;
  SimPanoramaArgs panorama;
};

/// Declares `sim` and its subcommands on `parent`; returns `sim`.
CLI::App* add_sim_command(CLI::App& parent, SimArgs& args);
/// Runs whichever subcommand was given; returns the process exit code.
int sim_command(const CLI::App& sim, const SimArgs& args);

}  // namespace neopipe::apps
