#pragma once
// `neopipe sim arm`: drive the simulated SCARA arm through a list of tool-frame moves and report
// commanded against actual poses.

#include <CLI/CLI.hpp>
#include <string>

namespace neopipe::apps {

struct SimArmArgs {
  std::string world;
  std::string moves;
  std::string out;
};

/// Declares the options of the `arm` subcommand `cmd` (created by add_sim_command).
void add_sim_arm_options(CLI::App& cmd, SimArmArgs& args);
/// Runs it; returns the process exit code.
int sim_arm_command(const SimArmArgs& args);

}  // namespace neopipe::apps
