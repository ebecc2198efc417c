#pragma once
// Many journeys between random start/goal pairs that have a path, and the table of their outcomes.
// The pairs come from one seeded stream and each journey from (seed, trial index), so the results
// are the same for any number of threads.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "apps/nav_harness.hpp"
#include "apps/nav_outcome.hpp"
#include "nav/mapmaker/map_maker.hpp"

namespace neopipe::apps {

/// `count` routes between random distinct pairs the map-maker can connect, in draw order. Pairs it
/// cannot connect are skipped. Throws nav::mapmaker::MapError when no reachable pair turns up.
std::vector<nav::mapmaker::Route> draw_routes(const nav::mapmaker::MapMaker& maker,
                                              nav::mapmaker::CostCriterion criterion, std::int64_t count,
                                              std::uint64_t seed);

/// The seed of trial `index` in a run seeded by `seed`.
std::uint64_t trial_seed(std::uint64_t seed, std::int64_t index);

struct TrialRecord {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  Outcome outcome = Outcome::fail_lost;
  int recoveries = 0;
  std::int64_t frames = 0;
  double commanded_travel = 0;
  double true_travel = 0;
  std::string reason;                            ///< the navigator's, when it stopped aware of a failure
  std::optional<std::size_t> first_wrong_entry;  ///< the first custom-map entry that held a wrong object
};

struct TrialsSummary {
  std::vector<TrialRecord> trials;       ///< in trial order
  std::array<std::int64_t, 6> counts{};  ///< by Outcome
  std::int64_t frames = 0;
  double seconds = 0;  ///< wall time of the journeys
  double commanded_travel = 0;
  double true_travel = 0;

  std::int64_t count(Outcome o) const { return counts[static_cast<std::size_t>(o)]; }
  std::int64_t reached() const;
};

/// Runs every route as a journey (in parallel on `threads` threads, 0: all cores). `progress`, if
/// set, is called with the number of journeys done, from one thread at a time.
TrialsSummary run_trials(const sim::World& world, const std::vector<nav::mapmaker::Route>& routes,
                         const JourneySettings& settings, int threads,
                         const std::function<void(std::int64_t)>& progress = {});

}  // namespace neopipe::apps
