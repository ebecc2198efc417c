#pragma once
// Every navigation system judged side by side (issue 21): the same world, the same random start and
// goal pairs, the same arm errors journey by journey (journey i of every system is seeded by
// trial_seed(seed, i)), the same outcomes assigned by the rig. Per system: the goal rate with its
// Wilson 95 % interval, the path it travelled against the straight line, the frames it read, and
// what it had to know beforehand; between every two systems an exact McNemar test on the journeys
// where one reached the goal and the other did not.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rig/journey.hpp"
#include "rig/navigation_system.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// One system in a comparison.
struct Contender {
  std::unique_ptr<NavigationSystem> system;
  /// What it had to know before its first journey, in a few words ("a surveyed map", "nothing").
  std::string knows;
};

/// Plans of every contender over the same pairs: plans[s][i] is system s's plan of pair i.
struct CommonPlans {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<std::vector<std::unique_ptr<Plan>>> plans;
  std::int64_t draws = 0;  ///< pairs drawn (distinct start and goal)
  /// Per system: drawn pairs it could not plan, of those every system before it could.
  std::vector<std::int64_t> unplanned;
};

/// `count` random pairs of distinct objects that every system can plan (the first UnreachableGoal
/// skips the pair for all; the systems after it are not asked), drawn from one stream of `seed` as rig::draw_plans
/// draws. Throws std::runtime_error when too few such pairs turn up, std::invalid_argument for no systems.
CommonPlans draw_common_plans(const std::vector<const NavigationSystem*>& systems, std::size_t objects,
                              std::int64_t count, std::uint64_t seed);

struct ComparisonSettings {
  std::int64_t trials = 1000;
  JourneySettings journey;  ///< its seed draws the pairs and seeds every journey
  int threads = 0;          ///< 0: all cores
};

/// One system's journeys.
struct ContenderResult {
  std::string system;
  std::string knows;
  TrialsSummary summary;
  std::int64_t unplanned = 0;  ///< drawn pairs it could not plan, of those the systems before it could
  double mean_path_ratio =
      0;  ///< arm travel / the straight line between the tool's ends, journeys that reached the goal
  double median_path_ratio = 0;  ///< the same, median
  double mean_frames = 0;        ///< per journey run
};

/// The exact McNemar test between systems a and b (indices into Comparison::results).
struct PairedTest {
  std::size_t a = 0;
  std::size_t b = 0;
  PairedComparison result;
};

struct Comparison {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::int64_t draws = 0;
  std::vector<ContenderResult> results;  ///< in the order of the contenders
  std::vector<PairedTest> tests;         ///< every a < b
  double seconds = 0;                    ///< wall time of every journey of every system
};

/// Called as journeys end: the system's index and its journeys done so far.
using ComparisonProgress = std::function<void(std::size_t system, std::int64_t done)>;

/// Plans the common pairs and runs every contender's journeys on `world` (the world the systems
/// were made for). Throws as draw_common_plans.
Comparison compare_systems(const std::vector<Contender>& contenders, const sim::World& world,
                           const ComparisonSettings& settings, const ComparisonProgress& progress = {});

/// {"pairs": n, "draws": d, "systems": [{"system", "knows", "journeys", "reached_goal",
/// "reached_goal_rate", "reached_goal_ci95", "outcomes", "unplanned", "path_ratio_mean",
/// "path_ratio_median", "frames_mean", "seconds"}...], "mcnemar": [{"a", "b", "a_only", "b_only",
/// "p_value"}...], "seconds"}.
nlohmann::json comparison_json(const Comparison& comparison);

}  // namespace neopipe::rig
