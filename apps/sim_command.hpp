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

struct SimArgs {
  SimWorldArgs world;
  SimArmArgs arm;
};

/// Declares `sim` and its subcommands on `parent`; returns `sim`.
CLI::App* add_sim_command(CLI::App& parent, SimArgs& args);
/// Runs whichever subcommand was given; returns the process exit code.
int sim_command(const CLI::App& sim, const SimArgs& args);

}  // namespace neopipe::apps
