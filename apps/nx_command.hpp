#pragma once
// `neopipe nx explore`: NX explores a world from a seeded start (qualnav.md §9) and its learned map
// is held against the true Voronoi graph of the marbles (OpenCV's subdivision): places, edges,
// distances of the places to the true vertices, edges found and missed.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace neopipe::apps {

struct NxArgs {
  std::string world;
  std::uint64_t seed = 1;
  double range_error = 0.10;
  std::int64_t places = 40;
  double sigma_move = 0.003;
  double sigma_rot = 0.002;
  double match_radius = 3;
  bool json = false;
  std::string plot;
};

CLI::App* add_nx_command(CLI::App& app, NxArgs& args);
/// Runs the subcommand of `nx` parsed.
int nx_command(const CLI::App& nx, const NxArgs& args);

}  // namespace neopipe::apps
