#include "rig/comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "rig/reports.hpp"
#include "sim/random.hpp"

namespace neopipe::rig {
namespace {

using nlohmann::json;

// The tool's travel over the straight line from where it started to where it ended, for the
// journeys that reached the goal (a journey that stopped early says nothing about the length of a
// path). Between the tool's own ends, not the two objects': systems start beside the start object
// at different offsets and hold the goal from different distances.
void path_ratios(const TrialsSummary& t, ContenderResult& r) {
  std::vector<double> ratios;
  for (const TrialRecord& j : t.trials) {
    if (j.refused || !reached_goal(j.outcome) || j.displacement <= 0) continue;
    ratios.push_back(j.true_travel / j.displacement);
  }
  if (ratios.empty()) return;
  double sum = 0;
  for (const double x : ratios) sum += x;
  r.mean_path_ratio = sum / static_cast<double>(ratios.size());
  const auto mid = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), mid, ratios.end());
  r.median_path_ratio = *mid;
  if (ratios.size() % 2 == 0) {
    r.median_path_ratio = (r.median_path_ratio + *std::max_element(ratios.begin(), mid)) / 2;
  }
}

}  // namespace

CommonPlans draw_common_plans(const std::vector<const NavigationSystem*>& systems, std::size_t objects,
                              std::int64_t count, std::uint64_t seed) {
  if (systems.empty()) throw std::invalid_argument("a comparison needs at least one system");
  if (objects < 2) throw std::runtime_error(fmt::format("a journey needs two objects; the world has {}", objects));
  const auto n = static_cast<std::uint64_t>(objects);
  CommonPlans common;
  common.plans.resize(systems.size());
  common.unplanned.assign(systems.size(), 0);
  sim::Random random(seed);  // the stream rig::draw_plans reads: one system alone meets the same pairs
  const std::int64_t max_attempts = 100 * count + 10000;
  for (std::int64_t attempt = 0; attempt < max_attempts && std::ssize(common.pairs) < count; ++attempt) {
    const auto from = static_cast<std::uint32_t>(random.next() % n);
    const auto to = static_cast<std::uint32_t>(random.next() % n);
    if (from == to) continue;
    ++common.draws;
    std::vector<std::unique_ptr<Plan>> plans(systems.size());
    bool all = true;
    // The first system that cannot plan the pair drops it: the later ones need not plan it (a
    // Qualnav plan teaches a route, a Park & Kender plan searches the map: most of a comparison's
    // time when the first system connects few pairs).
    for (std::size_t s = 0; s < systems.size() && all; ++s) {
      try {
        plans[s] = systems[s]->plan(from, to);
      } catch (const UnreachableGoal&) {
        ++common.unplanned[s];
        all = false;
      }
    }
    if (!all) continue;
    common.pairs.emplace_back(from, to);
    for (std::size_t s = 0; s < systems.size(); ++s) common.plans[s].push_back(std::move(plans[s]));
  }
  if (std::ssize(common.pairs) < count) {
    throw std::runtime_error(
        fmt::format("found only {} start/goal pairs that every system can plan, of {} wanted, in {} draws",
                    common.pairs.size(), count, common.draws));
  }
  return common;
}

Comparison compare_systems(const std::vector<Contender>& contenders, const sim::World& world,
                           const ComparisonSettings& settings, const ComparisonProgress& progress) {
  std::vector<const NavigationSystem*> systems;
  for (const Contender& c : contenders) systems.push_back(c.system.get());
  const auto start = std::chrono::steady_clock::now();
  CommonPlans common = draw_common_plans(systems, world.objects.size(), settings.trials, settings.journey.seed);
  Comparison out;
  out.pairs = common.pairs;
  out.draws = common.draws;
  for (std::size_t s = 0; s < contenders.size(); ++s) {
    ContenderResult r;
    r.system = contenders[s].system->name();
    r.knows = contenders[s].knows;
    r.unplanned = common.unplanned[s];
    r.summary = run_trials(*contenders[s].system, common.plans[s], world, settings.journey, settings.threads,
                           [&](std::int64_t done) {
                             if (progress) progress(s, done);
                           });
    path_ratios(r.summary, r);
    r.mean_frames =
        static_cast<double>(r.summary.frames) / static_cast<double>(std::max<std::int64_t>(r.summary.run(), 1));
    out.results.push_back(std::move(r));
  }
  for (std::size_t a = 0; a < out.results.size(); ++a) {
    for (std::size_t b = a + 1; b < out.results.size(); ++b) {
      out.tests.push_back({a, b, compare_paired(out.results[a].summary, out.results[b].summary)});
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

json comparison_json(const Comparison& c) {
  json systems = json::array();
  for (const ContenderResult& r : c.results) {
    json s = {{"system", r.system},
              {"knows", r.knows},
              {"journeys", r.summary.run()},
              {"refused", r.summary.refused},
              {"unplanned", r.unplanned},
              {"path_ratio_mean", r.mean_path_ratio},
              {"path_ratio_median", r.median_path_ratio},
              {"frames_mean", r.mean_frames},
              {"seconds", r.summary.seconds}};
    s.update(outcome_tables_json(r.summary));
    systems.push_back(std::move(s));
  }
  json tests = json::array();
  for (const PairedTest& t : c.tests) {
    tests.push_back({{"a", c.results[t.a].system},
                     {"b", c.results[t.b].system},
                     {"journeys", t.result.journeys},
                     {"a_only", t.result.a_only},
                     {"b_only", t.result.b_only},
                     {"p_value", t.result.p_value}});
  }
  return {{"pairs", std::ssize(c.pairs)},
          {"draws", c.draws},
          {"systems", systems},
          {"mcnemar", tests},
          {"seconds", c.seconds}};
}

}  // namespace neopipe::rig
