#pragma once
// `neopipe compare`: every navigation system on the same world, the same random start/goal pairs and
// the same arm errors; per system the goal rate with its 95 % interval, path length against the
// straight line, frames and what it had to know beforehand, and exact McNemar tests between them.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace neopipe::apps {

struct CompareArgs {
  std::string world;
  std::int64_t trials = 1000;
  std::vector<std::string> systems;  ///< empty: all
  std::optional<double> sigma_map;   ///< Park & Kender's survey: none = the global camera
  std::string realism = "rig";
  std::string cost = "reliability";
  double sigma_move = 0.003;
  double sigma_rot = 0.002;
  double bearing_noise = 0;  ///< panoramic sensor, degrees
  std::int64_t images = 30;  ///< QRM's imaging tour
  std::int64_t k = 18;       ///< QRM's landmarks per image
  double qualnav_range_error = 0.5;
  double nx_range_error = 0.1;
  std::int64_t places = 40;  ///< NX's exploration budget
  std::uint64_t seed = 1;
  int threads = 0;
  bool json = false;
  std::string plot;
};

CLI::App* add_compare_command(CLI::App& app, CompareArgs& args);
int compare_command(const CompareArgs& args);

}  // namespace neopipe::apps
