#pragma once
// `neopipe sim arm`: drive the simulated SCARA arm through a list of tool-frame moves and report
// commanded against actual poses.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "sim/arm/angles.hpp"
#include "sim/arm/motion_model.hpp"

namespace neopipe::apps {

/// Error coefficients in the command line's units (mm and degrees); defaults are sim::MotionErrors{}.
struct SimArmErrorArgs {
  double sigma0 = sim::MotionErrors{}.translation_sigma0;                     ///< mm
  double along_per_mm = sim::MotionErrors{}.along_per_mm;                     ///< mm per mm
  double across_per_mm = sim::MotionErrors{}.across_per_mm;                   ///< mm per mm
  double rot_sigma0_deg = sim::degrees(sim::MotionErrors{}.rotation_sigma0);  ///< deg
  double rot_per_mm_deg = sim::degrees(sim::MotionErrors{}.rotation_per_mm);  ///< deg per mm
  double rot_per_deg = sim::MotionErrors{}.rotation_per_rad;                  ///< deg per deg
  bool none = false;
};

struct SimArmArgs {
  std::string world;
  std::string moves;
  std::string out;    ///< empty: stdout
  std::string start;  ///< "x,y,theta" (mm, mm, deg); empty: the workspace centre, heading 0
  std::string base;   ///< "x,y" mm; empty: sized for the workspace
  std::string links;  ///< "l1,l2" mm; empty: sized for the workspace
  std::uint64_t seed = 1;
  SimArmErrorArgs errors;
};

/// Declares the options of the `arm` subcommand `cmd` (created by add_sim_command).
void add_sim_arm_options(CLI::App& cmd, SimArmArgs& args);
/// Runs it; returns the process exit code.
int sim_arm_command(const SimArmArgs& args);

}  // namespace neopipe::apps
