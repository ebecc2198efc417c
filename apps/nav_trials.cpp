#include "apps/nav_trials.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

#include "sim/random.hpp"

namespace neopipe::apps {

namespace mm = nav::mapmaker;

std::vector<mm::Route> draw_routes(const mm::MapMaker& maker, mm::CostCriterion criterion, std::int64_t count,
                                   std::uint64_t seed) {
  const auto n = static_cast<std::uint64_t>(maker.workspace().objects.size());
  std::vector<mm::Route> routes;
  routes.reserve(static_cast<std::size_t>(count));
  sim::Random random(seed);
  // Generous: even a world where one pair in a hundred connects fills its quota; a world where none
  // does must still end with an error rather than loop.
  const std::int64_t max_attempts = 100 * count + 10000;
  for (std::int64_t attempt = 0; attempt < max_attempts && std::ssize(routes) < count; ++attempt) {
    const auto from = static_cast<std::uint32_t>(random.next() % n);
    const auto to = static_cast<std::uint32_t>(random.next() % n);
    if (from == to) continue;
    try {
      routes.push_back(maker.plan(from, to, criterion));
    } catch (const mm::UnreachableGoal&) {
    }
  }
  if (std::ssize(routes) < count) {
    throw mm::MapError(fmt::format("found only {} reachable start/goal pairs of {} wanted in {} random draws",
                                   routes.size(), count, max_attempts));
  }
  return routes;
}

std::uint64_t trial_seed(std::uint64_t seed, std::int64_t index) {
  sim::Random r(seed * 0x100000001B3ULL + static_cast<std::uint64_t>(index));
  return r.next();
}

std::int64_t TrialsSummary::reached() const {
  return count(Outcome::success_direct) + count(Outcome::success_recovered) + count(Outcome::success_unaware);
}

TrialsSummary run_trials(const sim::World& world, const std::vector<mm::Route>& routes, const JourneySettings& settings,
                         int threads, const std::function<void(std::int64_t)>& progress) {
  TrialsSummary summary;
  summary.trials.resize(routes.size());
  std::atomic<std::int64_t> done{0};
  std::mutex progress_mutex;
  const auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  arena.execute([&] {
    // One journey per task: journeys last thousands of frames, so scheduling costs nothing.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, routes.size(), 1), [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            JourneySettings s = settings;
            s.seed = trial_seed(settings.seed, static_cast<std::int64_t>(i));
            const JourneyResult r = run_journey(world, routes[i], s);
            TrialRecord& t = summary.trials[i];
            t = {routes[i].start,    routes[i].goal, r.outcome,       r.report.recoveries, r.frames,
                 r.commanded_travel, r.true_travel,  r.report.reason, std::nullopt};
            const auto wrong =
                std::find_if(r.held.begin(), r.held.end(), [](const HeldLandmark& h) { return !h.correct; });
            if (wrong != r.held.end()) t.first_wrong_entry = wrong->entry;
            ++done;
            if (progress) {
              const std::scoped_lock lock(progress_mutex);
              progress(done.load());  // read under the lock: the bar never goes backwards
            }
          }
        });
  });
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Sums in trial order, so the totals do not depend on which thread finished first.
  for (const TrialRecord& t : summary.trials) {
    ++summary.counts[static_cast<std::size_t>(t.outcome)];
    summary.frames += t.frames;
    summary.commanded_travel += t.commanded_travel;
    summary.true_travel += t.true_travel;
  }
  return summary;
}

}  // namespace neopipe::apps
