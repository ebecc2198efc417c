#pragma once
// `neopipe map stats`: parkway statistics over random worlds (paper Fig. 7 and Fig. 11) as CSV and a
// PNG plot, against the paper's Poisson estimate. Defined apart from `neopipe map` so that the two
// commands' files change independently.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace neopipe::apps {

struct MapStatsArgs {
  double size = 100;                  ///< world side, mm
  std::string window = "2..10";       ///< window sides: A..B[:STEP] (step 1) or a list
  std::string population = "0..400";  ///< populations: A..B[:STEP] (step 20) or a list
  std::int64_t trials = 20;
  std::uint64_t seed = 1;
  int threads = 0;
  double margin_factor = 0.05;
  std::string csv;   ///< empty: stdout
  std::string plot;  ///< PNG
  bool quiet = false;
  std::string shard;  ///< --shard I/K: rows of shard I of K (neopipe batch merge-shards)
};

/// Adds `stats` under `map` (which then needs no --world): call after add_map_command.
CLI::App* add_map_stats_command(CLI::App* map, MapStatsArgs& args);
int map_stats_command(const MapStatsArgs& args);

/// "A..B[:STEP]" (STEP defaults to `default_step`) or "A,B,C": the values, ascending as written.
/// Throws UsageError naming `option` for anything else.
std::vector<double> parse_range(const std::string& text, const std::string& option, double default_step);

}  // namespace neopipe::apps
