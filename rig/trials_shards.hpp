#pragma once
// `neopipe nav --trials N --shard I/K`: journeys I of K of one trials run, and their merge into the
// trials JSON the unsharded run prints. Every shard draws the same N plans (one seeded stream) and
// runs journeys first..last-1 of them, journey i seeded by trial_seed(seed, i) as in the unsharded
// run; so each journey's record is the same bytes in both, and the merge recomputes every total
// from the journeys in trial order with the same arithmetic as the unsharded run.
//
// Wall time ("seconds", "frames_per_second") depends on the machine and the moment: no merge can
// reproduce it. The merged JSON leaves those two fields out; everything else is byte-identical to
// `neopipe nav --trials N --json` with those two fields deleted (docs/cluster.md).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace neopipe::rig {

/// The journeys one shard runs: [first, last) of `trials`, shard `index` of `count`.
struct TrialShard {
  std::int64_t index = 0;
  std::int64_t count = 1;
  std::int64_t trials = 0;
  std::int64_t first = 0;
  std::int64_t last = 0;
};

/// Keys of a journey's record that only the totals need; trials_json removes them.
inline constexpr const char* kJourneyCommandedTravel = "commanded_travel";
inline constexpr const char* kJourneyPlannedDistance = "planned_distance";

/// The trials JSON from `config` (the run's settings: cost, seed, survey, ...) and the journeys'
/// records in trial order (each with the raw kJourney* fields): counts, rates, means and recoveries
/// recomputed from the records. `seconds` (wall time) adds "seconds" and "frames_per_second".
nlohmann::json trials_json(const nlohmann::json& config, nlohmann::json journeys, std::optional<double> seconds);

/// One shard's output: `config`, the shard, its journeys' records (raw fields kept) and its wall time.
nlohmann::json trials_shard_json(const nlohmann::json& config, const nlohmann::json& journeys, const TrialShard& shard,
                                 double seconds);

/// Merges every shard of one run (any order) into trials_json(config, journeys, nullopt). Throws
/// std::invalid_argument naming the file (`names[i]`) for a file that is no shard, shards of different
/// runs (settings, N or K differ), or a shard missing or given twice.
nlohmann::json merge_trials_shards(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& names);

}  // namespace neopipe::rig
