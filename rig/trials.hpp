#pragma once
// Many journeys between random start/goal pairs that have a path, the table of their outcomes, and
// journey-by-journey comparisons of two runs. The pairs come from one seeded stream and each
// journey from (seed, trial index), so results are the same for any number of threads, and two
// runs with the same seed (another criterion, recovery off, another system) meet the same pairs
// with the same noise.

#include <any>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rig/journey.hpp"
#include "rig/navigation_system.hpp"
#include "rig/outcome.hpp"

namespace neopipe::rig {

/// `count` plans between random distinct pairs of `objects` objects that `system` can connect, in
/// draw order; pairs it cannot connect are skipped. Throws std::runtime_error when too few
/// reachable pairs turn up.
std::vector<std::unique_ptr<Plan>> draw_plans(const NavigationSystem& system, std::size_t objects, std::int64_t count,
                                              std::uint64_t seed);

struct TrialRecord {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  Outcome outcome = Outcome::fail_lost;
  int recoveries = 0;  ///< of every kind
  int backtracks = 0;  ///< of which returns to an earlier landmark
  std::int64_t frames = 0;
  double commanded_travel = 0;
  double true_travel = 0;
  double displacement = 0;  ///< mm from where the tool started to where it ended, straight, as the truth has it
  double planned_reliability = 1;
  bool refused = false;                          ///< not attempted (Plan::refused): no outcome
  std::string reason;                            ///< the system's, when it stopped aware of a failure or refused
  std::optional<std::size_t> first_wrong_entry;  ///< the first entry that held a wrong object
  std::any details;                              ///< the system's own report (Travel::details)
};

struct TrialsSummary {
  std::vector<TrialRecord> trials;       ///< in trial order
  std::array<std::int64_t, 6> counts{};  ///< by Outcome, over the journeys run
  std::int64_t refused = 0;              ///< plans the system refused (not run, not in counts)
  std::int64_t frames = 0;
  double seconds = 0;  ///< wall time of the journeys
  double commanded_travel = 0;
  double true_travel = 0;

  [[nodiscard]] std::int64_t count(Outcome o) const { return counts[static_cast<std::size_t>(o)]; }
  [[nodiscard]] std::int64_t reached() const;
  [[nodiscard]] double mean_planned_reliability() const;  ///< over the journeys run
  [[nodiscard]] std::int64_t run() const { return static_cast<std::int64_t>(trials.size()) - refused; }
};

/// Runs every plan as a journey (in parallel on `threads` threads, 0: all cores), journey i seeded
/// by trial_seed(settings.seed, first_trial + i) (first_trial: where these plans start in a larger
/// run that is split into shards). `progress`, if set, is called with the number of journeys done,
/// from one thread at a time.
TrialsSummary run_trials(const NavigationSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                         const sim::World& world, const JourneySettings& settings, int threads,
                         const std::function<void(std::int64_t)>& progress = {}, std::int64_t first_trial = 0);

/// Two runs over the same journeys, compared journey by journey.
struct PairedComparison {
  std::int64_t journeys = 0;
  std::int64_t a_reached = 0;
  std::int64_t b_reached = 0;
  std::int64_t a_only = 0;  ///< journeys that reach the goal in run a and not in run b
  std::int64_t b_only = 0;
  double p_value = 1;  ///< exact two-sided McNemar test on a_only against b_only
};

/// Throws std::invalid_argument unless both runs made the same journeys (same pairs, same order).
PairedComparison compare_paired(const TrialsSummary& a, const TrialsSummary& b);

}  // namespace neopipe::rig
