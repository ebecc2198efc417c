#pragma once
// `neopipe sim panorama`: the panoramic sensor's ring image at a tool pose (qualnav.md §2), as a
// false-colour picture, and what a navigator reads from it.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace neopipe::apps {

struct SimPanoramaArgs {
  std::string world;
  std::string at;  ///< x,y[,heading] (mm, mm, degrees)
  std::string out;
  bool json = false;
  double noise = 0;  ///< sd of each disc's bearing jitter, degrees
  double range = 600;
  std::uint64_t seed = 1;
};

/// Declares the options of the `panorama` subcommand `cmd` (created by add_sim_command).
void add_sim_panorama_options(CLI::App& cmd, SimPanoramaArgs& args);
/// Runs it; returns the process exit code.
int sim_panorama_command(const SimPanoramaArgs& args);

}  // namespace neopipe::apps
