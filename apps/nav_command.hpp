#pragma once
// `neopipe nav`: the navigator in the simulator. One journey (--from/--to) with its custom map,
// outcome and per-entry account, optionally plotted and filmed; or --trials N random journeys and
// the table of their outcomes (park-kender.md §9) with 95% intervals, frames and arm travel.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace neopipe::apps {

struct NavArgs {
  std::string system = "park-kender";  ///< park-kender | qrm | qualnav | nx
  std::string world;
  std::optional<std::int64_t> from;
  std::optional<std::int64_t> to;
  /// A journey's job is to arrive: the most reliable path by default. The paper's compromise (ratio)
  /// travels ~10% less and reaches the goal in 99.0-99.6% of journeys against 99.7-100% on five sets
  /// of 1,000 (docs/navigation-experiments.md).
  std::string cost = "reliability";
  std::optional<double> sigma_map;  ///< none: the survey goes through the global camera and calibration
  std::string realism = "rig";      ///< both cameras' realism preset
  std::string cache_dir;            ///< of calibration sessions; empty: the default folder
  bool no_cache = false;
  double sigma_move = 0.003;
  double sigma_rot = 0.002;
  std::uint64_t seed = 1;
  std::optional<std::int64_t> trials;
  std::optional<std::int64_t> as_trial;
  bool no_recovery = false;
  bool no_slide_goals = false;
  std::string navigator = "tracking";     ///< tracking | paper
  std::string descriptions = "extended";  ///< paper | extended
  double min_reliability = 0;             ///< refuse routes forecast below this
  std::string diagram;                    ///< --reliability-diagram PNG
  std::string survey_csv;                 ///< --survey-csv: what the map-maker believes, beside the truth
  std::string shard;                      ///< --shard I/K: journeys of shard I of K (neopipe batch merge-shards)
  double window = 50;
  int threads = 0;
  bool json = false;
  std::string plot;
  std::string video;
  std::int64_t images = 30;  ///< qrm: imaging positions of the tour that builds the map
  std::int64_t k = 18;       ///< qrm: the k nearest landmarks of an image are fused (spec qrm.md §9)
  std::string pairs;         ///< qrm: journeys between the pairs of a trials JSON instead of random draws
  /// qualnav: the range estimates' error e, factors in [1/(1+e), 1+e] (default 0.5); nx: the range
  /// ring's relative error bound (default 0.1).
  std::optional<double> range_error;
  std::int64_t places = 40;               ///< nx: the exploration's budget of places
  std::string taught_route = "shortest";  ///< qualnav: shortest | detour
  std::string level = "viewframes";       ///< qualnav: the level journeys start at, viewframes | regions
};

CLI::App* add_nav_command(CLI::App& app, NavArgs& args);
int nav_command(const NavArgs& args);
/// `neopipe nav --system qrm` (apps/nav_qrm.cpp).
int qrm_nav_command(const NavArgs& args);
/// `neopipe nav --system nx` (apps/nav_nx.cpp).
int nx_nav_command(const NavArgs& args);
/// `neopipe nav --system qualnav` (apps/nav_qualnav.cpp).
int qualnav_nav_command(const NavArgs& args);

}  // namespace neopipe::apps
