// `neopipe nav --system nx`: NX (rig/nx_system.hpp) through the same rig as the other systems: it
// explores the world first (knowing nothing), then one journey or trials with the same JSON keys.

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/cli_support.hpp"
#include "apps/nav_command.hpp"
#include "apps/nav_journey_support.hpp"
#include "apps/nx_plot.hpp"
#include "apps/outcome_table.hpp"
#include "apps/progress.hpp"
#include "rig/journey.hpp"
#include "rig/nx_system.hpp"
#include "rig/seeds.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

// --range-error: its default is this system's own.
double nx_range_error(const NavArgs& a) {
  return a.range_error.value_or(0.10);
}

namespace nx = nav::nx;
using nlohmann::json;

int nx_one_journey(const NavArgs& a, const sim::World& world, const rig::NxSystem& system) {
  PlannedJourney planned = plan_one_journey(a, world, system);
  if (!planned.plan) return kExitUnreachable;
  const std::unique_ptr<rig::Plan>& plan = planned.plan;
  const rig::JourneySettings& journey = planned.settings;
  const std::uint32_t from = plan->start;
  const std::uint32_t to = plan->goal;
  const rig::JourneyResult r = rig::run_journey(system, *plan, world, journey);
  const auto* report = std::any_cast<nx::NxJourney>(&r.travel.details);
  const rig::NxPlan& p = rig::nx_plan(*plan);
  if (!a.plot.empty()) write_nx_plot(a.plot, world, system.exploration(), nullptr, r.arm.track);
  const json held = held_landmarks_json(r);
  const std::vector<std::size_t> visited = report != nullptr ? report->places : std::vector<std::size_t>{};
  const char* ending = report != nullptr ? nx::journey_ending_name(report->ending) : "none";
  if (a.json) {
    std::cout << json{{"system", "nx"},
                      {"from", from},
                      {"to", to},
                      {"planned_places", p.route},
                      {"goal_bearing_deg", p.goal_bearing_deg},
                      {"places", visited},
                      {"held", held},
                      {"outcome", rig::outcome_name(r.outcome)},
                      {"reached_goal", rig::reached_goal(r.outcome)},
                      {"ending", ending},
                      {"reason", r.travel.reason},
                      {"legs", report != nullptr ? report->legs : 0},
                      {"relocalisations", report != nullptr ? report->relocalisations : 0},
                      {"frames", r.frames},
                      {"commanded_travel", r.arm.commanded_travel},
                      {"arm_travel", r.arm.true_travel},
                      {"refused_moves", r.arm.refused_moves},
                      {"exploration", rig::nx_exploration_json(system.exploration())},
                      {"seed", a.seed}}
                     .dump()
              << '\n';
    return kExitOk;
  }
  const auto ids = [](const auto& v) { return fmt::format("{}", fmt::join(v, " -> ")); };
  std::cout << fmt::format("places {} -> {} on the learned map: {} (goal bearing {:.1f}°)\n", from, to, ids(p.route),
                           p.goal_bearing_deg)
            << fmt::format("places visited: {}\n", ids(visited))
            << fmt::format("outcome: {} (NX: {}{}{})\n", rig::outcome_name(r.outcome), ending,
                           r.travel.reason.empty() ? "" : ", ", r.travel.reason)
            << fmt::format("{} frames; commanded travel {:.1f} mm, arm travel {:.1f} mm\n", r.frames,
                           r.arm.commanded_travel, r.arm.true_travel);
  return kExitOk;
}

int nx_trials(const NavArgs& a, const sim::World& world, const rig::NxSystem& system) {
  const std::vector<std::unique_ptr<rig::Plan>> plans =
      rig::draw_plans(system, world.objects.size(), *a.trials, a.seed);
  ProgressBar bar("nav", std::ssize(plans), true);
  const rig::TrialsSummary t = rig::run_trials(system, plans, world, arm_journey_settings(a), a.threads,
                                               [&](std::int64_t done) { bar.update(done); });
  bar.clear();
  json j = rig::nx_trials_json(system, plans, t);
  j["world"] = a.world;
  j["seed"] = a.seed;
  j["sigma_move"] = a.sigma_move;
  j["sigma_rot"] = a.sigma_rot;
  if (a.json) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  const rig::NxExploration& e = system.exploration();
  std::cout << fmt::format(
      "{} journeys on {} ({} objects), system nx (explored: {} places, {} edges; range error {}), move {} /mm, "
      "rotation {} deg/mm, seed {}\n\n{:<20} {:>7} {:>8}  {}\n",
      n, a.world, world.objects.size(), e.report.places, e.report.edges, nx_range_error(a), a.sigma_move, a.sigma_rot,
      a.seed, "OUTCOME", "COUNT", "RATE", "95% CI");
  print_outcome_rows(std::cout, t, n);
  std::cout << "\nNX's endings:";
  for (const auto& [name, count] : j["nx"]["endings"].items()) {
    std::cout << fmt::format(" {} {}", name, count.get<std::int64_t>());
  }
  std::cout << fmt::format("\nframes {} in {:.2f} s; mean arm travel {:.1f} mm\n", t.frames, t.seconds,
                           j["mean_arm_travel"].get<double>());
  return kExitOk;
}

}  // namespace

int nx_nav_command(const NavArgs& a) {
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (a.from.has_value() == a.trials.has_value()) {
    throw UsageError{"give either --from I --to J (one journey) or --trials N (random journeys)"};
  }
  if (a.trials && *a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", *a.trials)};
  if (!a.from && !a.plot.empty()) throw UsageError{"--plot draws one journey: use it with --from/--to"};
  if (!a.from && a.as_trial) throw UsageError{"--as-trial replays one journey: give --from/--to"};
  if (!a.diagram.empty()) throw UsageError{"--reliability-diagram is Park & Kender's: NX makes no forecast"};
  if (!a.video.empty()) throw UsageError{"--video is Park & Kender's onboard view"};
  if (!a.pairs.empty()) throw UsageError{"--pairs goes with --system qrm"};
  if (!(nx_range_error(a) >= 0 && nx_range_error(a) < 1)) {
    throw UsageError{fmt::format("--range-error {}: must lie in [0, 1)", nx_range_error(a))};
  }
  if (a.places < 1) throw UsageError{fmt::format("--places {}: must be at least 1", a.places)};
  if (!(a.sigma_move >= 0) || !(a.sigma_rot >= 0) || !std::isfinite(a.sigma_move) || !std::isfinite(a.sigma_rot)) {
    throw UsageError{"--sigma-move and --sigma-rot must be finite and not negative"};
  }
  const sim::World world = sim::load_world(a.world);
  if (world.objects.size() < 3) {
    throw std::runtime_error(
        fmt::format("{}: NX needs at least three marbles, the world has {}", a.world, world.objects.size()));
  }
  rig::NxSettings s;
  s.seed = a.seed;
  s.range_error = nx_range_error(a);
  s.arm = {a.sigma_move, a.sigma_rot};
  s.explore.max_places = static_cast<std::size_t>(a.places);
  ProgressBar bar("nav: NX exploring, places", a.places, true);
  rig::NxExploration e =
      rig::explore_world(world, s, [&](std::size_t done) { bar.update(static_cast<std::int64_t>(done)); });
  bar.clear();
  const rig::NxSystem system(world, std::move(e), s);
  return a.from ? nx_one_journey(a, world, system) : nx_trials(a, world, system);
}

}  // namespace neopipe::apps
