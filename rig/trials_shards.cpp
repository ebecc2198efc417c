#include "rig/trials_shards.hpp"

#include <fmt/format.h>

#include <map>
#include <stdexcept>

#include "rig/outcome.hpp"
#include "rig/reports.hpp"
#include "rig/trials.hpp"

namespace neopipe::rig {
using nlohmann::json;

namespace {

Outcome outcome_named(const std::string& name) {
  for (const Outcome o : kOutcomes)
    if (outcome_name(o) == name) return o;
  throw std::invalid_argument(fmt::format("unknown journey outcome '{}'", name));
}

}  // namespace

json trials_json(const json& config, json journeys, std::optional<double> seconds) {
  // The same sums, in the same order, as the unsharded run made them (trial order), so every digit
  // agrees: TrialsSummary's totals, then trials_report's means.
  TrialsSummary t;
  double mean_planned_distance_terms = 0;
  std::vector<double> planned_distances;
  std::int64_t backtracks = 0;
  std::int64_t rule_recoveries = 0;
  for (const json& j : journeys) {
    TrialRecord r;
    const std::string outcome = j.at("outcome").get<std::string>();
    r.refused = outcome == "refused";
    if (!r.refused) r.outcome = outcome_named(outcome);
    r.recoveries = j.at("recoveries").get<int>();
    r.backtracks = j.at("backtracks").get<int>();
    r.frames = j.at("frames").get<std::int64_t>();
    r.true_travel = j.at("arm_travel").get<double>();
    r.commanded_travel = j.at(kJourneyCommandedTravel).get<double>();
    r.planned_reliability = j.at("planned_reliability").get<double>();
    planned_distances.push_back(j.at(kJourneyPlannedDistance).get<double>());
    backtracks += r.backtracks;
    rule_recoveries += r.recoveries - r.backtracks;
    t.trials.push_back(r);
  }
  for (const TrialRecord& r : t.trials) {
    if (r.refused) {
      ++t.refused;
      continue;
    }
    ++t.counts[static_cast<std::size_t>(r.outcome)];
    t.frames += r.frames;
    t.commanded_travel += r.commanded_travel;
    t.true_travel += r.true_travel;
  }
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  for (std::size_t i = 0; i < t.trials.size(); ++i)
    if (!t.trials[i].refused) mean_planned_distance_terms += planned_distances[i] / static_cast<double>(n);
  for (json& j : journeys) {
    j.erase(kJourneyCommandedTravel);
    j.erase(kJourneyPlannedDistance);
  }
  json out = config;
  out.update({{"trials", std::ssize(t.trials)},
              {"run", t.run()},
              {"refused", t.refused},
              {"frames", t.frames},
              {"mean_arm_travel", t.true_travel / static_cast<double>(n)},
              {"mean_commanded_travel", t.commanded_travel / static_cast<double>(n)},
              {"mean_planned_reliability", t.mean_planned_reliability()},
              {"mean_planned_distance", mean_planned_distance_terms},
              {"recoveries", {{"qoc_rules", rule_recoveries}, {"backtracks", backtracks}}},
              {"journeys", std::move(journeys)}});
  if (seconds) {
    out["seconds"] = *seconds;
    out["frames_per_second"] = *seconds > 0 ? static_cast<double>(t.frames) / *seconds : 0;
  }
  out.update(outcome_tables_json(t));
  return out;
}

json trials_shard_json(const json& config, const json& journeys, const TrialShard& s, double seconds) {
  json out = {
      {"config", config},
      {"shard", {{"index", s.index}, {"count", s.count}, {"trials", s.trials}, {"first", s.first}, {"last", s.last}}},
      {"journeys", journeys},
      {"seconds", seconds}};
  return out;
}

json merge_trials_shards(const std::vector<json>& shards, const std::vector<std::string>& names) {
  std::map<std::int64_t, std::size_t> by_index;
  std::int64_t count = -1;
  std::int64_t trials = -1;
  const auto name_of = [&](std::size_t i) { return i < names.size() ? names[i] : fmt::format("shard {}", i); };
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const json& s = shards[i];
    if (!s.is_object() || !s.contains("shard") || !s.contains("config") || !s.contains("journeys")) {
      throw std::invalid_argument(
          fmt::format("{}: not a nav trials shard (neopipe nav --trials N --shard I/K --json)", name_of(i)));
    }
    const json& sh = s.at("shard");
    const auto index = sh.at("index").get<std::int64_t>();
    if (count >= 0 && (sh.at("count").get<std::int64_t>() != count || sh.at("trials").get<std::int64_t>() != trials)) {
      throw std::invalid_argument(fmt::format("{}: shard of {} trials in {} shards, the others of {} in {}", name_of(i),
                                              sh.at("trials").get<std::int64_t>(), sh.at("count").get<std::int64_t>(),
                                              trials, count));
    }
    count = sh.at("count").get<std::int64_t>();
    trials = sh.at("trials").get<std::int64_t>();
    if (s.at("config") != shards[0].at("config")) {
      throw std::invalid_argument(
          fmt::format("{}: another run's shard (its settings differ from {}'s)", name_of(i), name_of(0)));
    }
    if (by_index.count(index)) {
      throw std::invalid_argument(
          fmt::format("{}: shard {}/{} given twice (also {})", name_of(i), index, count, name_of(by_index[index])));
    }
    by_index[index] = i;
  }
  if (shards.empty()) throw std::invalid_argument("no shards given");
  json journeys = json::array();
  std::int64_t expect = 0;
  for (std::int64_t k = 0; k < count; ++k) {
    const auto it = by_index.find(k);
    if (it == by_index.end()) throw std::invalid_argument(fmt::format("shard {}/{} is missing", k, count));
    const json& s = shards[it->second];
    if (s.at("shard").at("first").get<std::int64_t>() != expect) {
      throw std::invalid_argument(
          fmt::format("{}: its journeys do not follow journey {}", name_of(it->second), expect));
    }
    for (const json& j : s.at("journeys")) journeys.push_back(j);
    expect = s.at("shard").at("last").get<std::int64_t>();
  }
  if (expect != trials || std::ssize(journeys) != trials) {
    throw std::invalid_argument(fmt::format("the shards hold {} of {} journeys", journeys.size(), trials));
  }
  return trials_json(shards[0].at("config"), std::move(journeys), std::nullopt);
}

}  // namespace neopipe::rig
