#pragma once
// What `neopipe map --json` and `neopipe nav --trials N --json` print, built here so that the command
// line (which only parses and prints) and the Python module (neopipe.map, neopipe.nav.trials) give
// the same dictionaries from the same requests.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nav/mapmaker/map_maker.hpp"
#include "rig/experiment.hpp"
#include "rig/navigation_system.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "rig/trials_shards.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// A request's option out of range (a negative window, an object id below 0, ...): the caller's
/// mistake, which the command line reports as a usage error. The message names the option as the
/// command line spells it.
class RequestError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// ---------------------------------------------------------------------------------------------------------------
// neopipe map

struct MapRequest {
  std::string world;                    ///< world YAML (neopipe sim world)
  std::string blobs;                    ///< or a blob table with X,Y (neopipe run --calib), its first frame
  std::optional<Eigen::Vector2d> size;  ///< workspace for `blobs`, mm (default 500 x 500)
  double window = 50;
  std::optional<double> margin;
  std::optional<double> sigma;
  double border_tolerance = 0;
  std::string descriptions = "extended";  ///< paper | extended
  std::string calib;                      ///< σ from its held-out error
  double move_error = 0.003;              ///< across-track sd per mm moved
  double rotation_error = 0.002;          ///< heading sd, degrees per mm moved
  std::optional<std::int64_t> from;
  std::optional<std::int64_t> to;
  std::string cost = "ratio";
  double reliable_threshold = 0.9;
};

struct MapReport {
  std::unique_ptr<nav::mapmaker::MapMaker> maker;
  std::optional<nav::mapmaker::Route> route;
  std::string unreachable;  ///< why from -> to has no route (empty: it has one, or none was asked)
  nlohmann::json json;      ///< `neopipe map --json`'s object
};

/// Builds the map. Throws RequestError for a bad option, MapError (or WorldError's message as one)
/// for a world that cannot be mapped; an unreachable goal is not an error (MapReport::unreachable).
MapReport map_report(const MapRequest& request);

// ---------------------------------------------------------------------------------------------------------------
// neopipe nav

struct NavRequest {
  std::string world;
  std::string cost = "reliability";
  std::optional<double> sigma_map;  ///< none: the survey goes through the global camera and calibration
  std::string realism = "rig";
  std::string cache_dir;  ///< of calibration sessions; empty: the default folder
  bool no_cache = false;
  double sigma_move = 0.003;
  double sigma_rot = 0.002;
  std::uint64_t seed = 1;
  bool no_recovery = false;
  bool no_slide_goals = false;
  std::string navigator = "tracking";     ///< tracking | paper
  std::string descriptions = "extended";  ///< paper | extended
  double min_reliability = 0;
  double window = 50;
  int threads = 0;
  std::function<void(const std::string&)> note;  ///< the survey's progress lines
};

struct NavSetup {
  sim::World world;
  Survey survey;
  ExperimentSettings settings;
};

/// The world, its survey and the settings derived from the request. Throws RequestError for a bad
/// option, WorldError and MapError for a world that cannot be navigated.
NavSetup nav_setup(const NavRequest& request);

/// The trials JSON's outcome tables, the same for every system: "outcomes" (counts), "rates" and
/// "ci95" (Wilson 95 % intervals) over the journeys run, and "reached_goal", "reached_goal_rate",
/// "reached_goal_ci95".
nlohmann::json outcome_tables_json(const TrialsSummary& t);

/// The keys every system's trials JSON begins with ("system", "trials", "run", "refused", "frames",
/// "seconds", "mean_arm_travel", "mean_commanded_travel") and its outcome tables; the system adds
/// its own key and "journeys".
nlohmann::json trials_report_json(const NavigationSystem& system, const TrialsSummary& t);

nlohmann::json survey_json(const Survey& survey);
/// "TRAJP 47 -> 75": a step's kind and ends, for grouping failures by kind.
std::string step_name(const nav::mapmaker::RouteStep& step);
/// Each planned step's kind, rated reliability and verifiability.
nlohmann::json steps_json(const nav::mapmaker::Route& route);

struct TrialsReport {
  std::vector<std::unique_ptr<Plan>> plans;
  TrialsSummary summary;
  nlohmann::json json;  ///< `neopipe nav --trials N --json`'s object
};

/// `trials` journeys between random reachable pairs (drawn from the request's seed), judged. With
/// `shard`, only its journeys run (summary.trials holds them alone) and the JSON is the shard's
/// (trials_shard_json), for merge_trials_shards.
TrialsReport trials_report(const NavRequest& request, const NavSetup& setup, std::int64_t trials,
                           const std::function<void(std::int64_t)>& progress = {},
                           const std::optional<TrialShard>& shard = std::nullopt);

}  // namespace neopipe::rig
