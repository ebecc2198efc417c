#include "rig/trials.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>

#include "rig/seeds.hpp"
#include "sim/random.hpp"

namespace neopipe::rig {

std::vector<std::unique_ptr<Plan>> draw_plans(const NavigationSystem& system, std::size_t objects, std::int64_t count,
                                              std::uint64_t seed) {
  if (objects < 2) throw std::runtime_error(fmt::format("a journey needs two objects; the world has {}", objects));
  const auto n = static_cast<std::uint64_t>(objects);
  std::vector<std::unique_ptr<Plan>> plans;
  plans.reserve(static_cast<std::size_t>(std::max<std::int64_t>(count, 0)));
  sim::Random random(seed);
  // Generous: even a world where one pair in a hundred connects fills its quota; a world where none
  // does must still end with an error rather than loop.
  const std::int64_t max_attempts = 100 * count + 10000;
  for (std::int64_t attempt = 0; attempt < max_attempts && std::ssize(plans) < count; ++attempt) {
    const auto from = static_cast<std::uint32_t>(random.next() % n);
    const auto to = static_cast<std::uint32_t>(random.next() % n);
    if (from == to) continue;
    try {
      plans.push_back(system.plan(from, to));
    } catch (const UnreachableGoal&) {
    }
  }
  if (std::ssize(plans) < count) {
    throw std::runtime_error(fmt::format("found only {} reachable start/goal pairs of {} wanted in {} random draws",
                                         plans.size(), count, max_attempts));
  }
  return plans;
}

std::int64_t TrialsSummary::reached() const {
  return count(Outcome::success_direct) + count(Outcome::success_recovered) + count(Outcome::success_unaware);
}

double TrialsSummary::mean_planned_reliability() const {
  if (trials.empty()) return 0;
  double sum = 0;
  std::int64_t run = 0;
  for (const TrialRecord& t : trials) {
    if (t.refused) continue;
    sum += t.planned_reliability;
    ++run;
  }
  return run > 0 ? sum / static_cast<double>(run) : 0;
}

TrialsSummary run_trials(const NavigationSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                         const sim::World& world, const JourneySettings& settings, int threads,
                         const std::function<void(std::int64_t)>& progress, std::int64_t first_trial) {
  TrialsSummary summary;
  summary.trials.resize(plans.size());
  std::atomic<std::int64_t> done{0};
  std::mutex progress_mutex;
  const auto start = std::chrono::steady_clock::now();
  const auto report_done = [&] {
    ++done;
    if (progress) {
      const std::scoped_lock lock(progress_mutex);
      progress(done.load());  // read under the lock: the bar never goes backwards
    }
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  arena.execute([&] {
    // One journey per task: journeys last thousands of frames, so scheduling costs nothing.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, plans.size(), 1), [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            JourneySettings s = settings;
            s.seed = trial_seed(settings.seed, first_trial + static_cast<std::int64_t>(i));
            const Plan& plan = *plans[i];
            TrialRecord& t = summary.trials[i];
            t.from = plan.start;
            t.to = plan.goal;
            t.planned_reliability = plan.planned_reliability;
            if (!plan.refused.empty()) {
              t.refused = true;
              t.reason = plan.refused;
              report_done();
              continue;
            }
            const JourneyResult r = run_journey(system, plan, world, s);
            t.outcome = r.outcome;
            t.recoveries = r.travel.recoveries;
            t.backtracks = r.travel.backtracks;
            t.frames = r.frames;
            t.commanded_travel = r.arm.commanded_travel;
            t.true_travel = r.arm.true_travel;
            if (r.arm.track.size() > 1) t.displacement = (r.arm.track.back() - r.arm.track.front()).norm();
            t.reason = r.travel.reason;
            t.details = r.travel.details;
            const auto wrong =
                std::find_if(r.held.begin(), r.held.end(), [](const HeldLandmark& h) { return !h.correct; });
            if (wrong != r.held.end()) t.first_wrong_entry = wrong->entry;
            report_done();
          }
        });
  });
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Sums in trial order, so the totals do not depend on which thread finished first.
  for (const TrialRecord& t : summary.trials) {
    if (t.refused) {
      ++summary.refused;
      continue;
    }
    ++summary.counts[static_cast<std::size_t>(t.outcome)];
    summary.frames += t.frames;
    summary.commanded_travel += t.commanded_travel;
    summary.true_travel += t.true_travel;
  }
  return summary;
}

PairedComparison compare_paired(const TrialsSummary& a, const TrialsSummary& b) {
  if (a.trials.size() != b.trials.size()) {
    throw std::invalid_argument(
        fmt::format("paired runs differ in length: {} and {} journeys", a.trials.size(), b.trials.size()));
  }
  PairedComparison c;
  c.journeys = std::ssize(a.trials);
  for (std::size_t i = 0; i < a.trials.size(); ++i) {
    const TrialRecord& x = a.trials[i];
    const TrialRecord& y = b.trials[i];
    if (x.from != y.from || x.to != y.to) {
      throw std::invalid_argument(
          fmt::format("paired runs differ at journey {}: {} -> {} against {} -> {}", i, x.from, x.to, y.from, y.to));
    }
    const bool ra = !x.refused && reached_goal(x.outcome);
    const bool rb = !y.refused && reached_goal(y.outcome);
    c.a_reached += ra ? 1 : 0;
    c.b_reached += rb ? 1 : 0;
    c.a_only += ra && !rb ? 1 : 0;
    c.b_only += rb && !ra ? 1 : 0;
  }
  c.p_value = mcnemar_p(c.a_only, c.b_only);
  return c;
}

}  // namespace neopipe::rig
