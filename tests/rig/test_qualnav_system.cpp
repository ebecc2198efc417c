// Qualnav's system in the rig (rig/qualnav_system.hpp): taught routes keep their clearance, the
// memory's viewpath follows them, journeys through the station's panoramic sensor and arm reach
// their goals keeping clear of the marbles and claim them 15 mm away, the trials JSON is the same
// on one thread and two, and a statistical test of the goal rate at the papers' 50 % range error.

#include <gtest/gtest.h>

#include <algorithm>
#include <any>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "rig/journey.hpp"
#include "rig/qualnav_system.hpp"
#include "rig/qualnav_teaching.hpp"
#include "rig/trials.hpp"
#include "sim/panorama.hpp"
#include "sim/world.hpp"

namespace {

namespace rig = neopipe::rig;
namespace qn = neopipe::nav::qualnav;
namespace sim = neopipe::sim;
using Eigen::Vector2d;

// Ten marbles on 250 x 250 mm, fixed here so the test does not move with the world generator.
sim::World small_world() {
  sim::World w;
  w.size = {250, 250};
  w.objects = {{30, 40},   {120, 30}, {210, 50},  {60, 120},  {150, 110},
               {220, 150}, {40, 210}, {110, 190}, {190, 220}, {125, 145}};
  return w;
}

TEST(QualnavTeaching, RoutesKeepTheirClearanceAndEndNearTheGoal) {
  const sim::World w = small_world();
  const Vector2d from = w.objects[0] + Vector2d(17.5, 0);
  const auto route = rig::teach_route(w, from, 8, 14, 20);
  ASSERT_TRUE(route.has_value());
  EXPECT_EQ(route->front(), from);
  EXPECT_NEAR((route->back() - w.objects[8]).norm(), 20, 2.1);
  const std::vector<Vector2d> samples = rig::sample_route(*route, 1);
  for (std::size_t k = 1; k < samples.size(); ++k) {
    EXPECT_TRUE(sim::keeps_clear(w, samples[k], 13)) << samples[k].transpose();
  }
  const std::vector<Vector2d> every20 = rig::sample_route(*route, 20);
  EXPECT_NEAR(static_cast<double>(every20.size()), std::ceil(rig::route_length(*route) / 20) + 1, 1);
  for (std::size_t k = 1; k < every20.size(); ++k) {
    EXPECT_LE((every20[k] - every20[k - 1]).norm(), 20 + 1e-9);  // 20 mm along the route, no more apart
    EXPECT_GT((every20[k] - every20[k - 1]).norm(), 0);
  }
}

TEST(QualnavSystem, JourneysReachTheirGoalsKeepingClearOfTheMarbles) {
  const sim::World w = small_world();
  rig::QualnavSettings s;
  const rig::QualnavSystem system(w, s);
  EXPECT_EQ(system.name(), "qualnav");
  EXPECT_EQ(system.camera().sensor, rig::Sensor::panoramic);
  const auto plans = rig::draw_plans(system, w.objects.size(), 8, 11);
  int reached = 0;
  for (const auto& plan : plans) {
    EXPECT_EQ(plan->landmarks, (std::vector<std::uint32_t>{plan->start, plan->goal}));
    rig::JourneySettings js;
    js.seed = 7;
    const rig::JourneyResult r = rig::run_journey(system, *plan, w, js);
    const qn::NavigationReport* report = rig::qualnav_report(r.travel);
    ASSERT_NE(report, nullptr);
    for (const Vector2d& p : r.arm.track) EXPECT_TRUE(sim::keeps_clear(w, p)) << p.transpose();
    if (rig::reached_goal(r.outcome)) {
      ++reached;
      ASSERT_FALSE(r.held.empty());
      // Stopped 15 mm from the goal's centre.
      EXPECT_NEAR((r.arm.track.back() - w.objects[plan->goal]).norm(), 15, 1.5);
    }
  }
  EXPECT_EQ(reached, std::ssize(plans));
}

TEST(QualnavSystem, TrialsAreTheSameOnOneThreadAndTwo) {
  const sim::World w = small_world();
  rig::QualnavSettings s;
  s.sensing.range_error = 1;
  s.detour = true;
  const rig::QualnavSystem system(w, s);
  const auto plans = rig::draw_plans(system, w.objects.size(), 6, 5);
  rig::JourneySettings js;
  js.seed = 9;
  nlohmann::json one = rig::qualnav_trials_json(system, plans, rig::run_trials(system, plans, w, js, 1));
  nlohmann::json two = rig::qualnav_trials_json(system, plans, rig::run_trials(system, plans, w, js, 2));
  one.erase("seconds");
  two.erase("seconds");
  EXPECT_EQ(one, two);
  EXPECT_EQ(one["qualnav"]["taught_routes"], "detour");
}

TEST(QualnavSystem, BadInput) {
  sim::World one;
  one.size = {100, 100};
  one.objects = {{50, 50}};
  EXPECT_THROW(rig::QualnavSystem(one, rig::QualnavSettings{}), std::invalid_argument);
  const sim::World w = small_world();
  rig::QualnavSettings s;
  s.sensing.range_error = -0.1;
  EXPECT_THROW(rig::QualnavSystem(w, s), std::invalid_argument);
  const rig::QualnavSystem system(w, rig::QualnavSettings{});
  EXPECT_THROW((void)system.plan(0, 0), std::invalid_argument);
  EXPECT_THROW((void)system.plan(0, 10), std::invalid_argument);
}

// The papers' claim at their 50 % range error, with power: 150 journeys must reach the goal in at
// least 145. At a true rate of 99.5 % this fails with probability 0.0001 (exact binomial), at 99 %
// with 0.004; at 97 % with 0.30, at 95 % (the target) with 0.77, at 92 % with 0.98: a drop of a few
// points below what it measures (rig journeys on this world: 100 %) fails it.
TEST(QualnavSystem, GoalRateAtFiftyPercentRangeError) {
  const sim::World w = small_world();
  const rig::QualnavSystem system(w, rig::QualnavSettings{});
  const auto plans = rig::draw_plans(system, w.objects.size(), 150, 21);
  rig::JourneySettings js;
  js.seed = 4;
  const rig::TrialsSummary t = rig::run_trials(system, plans, w, js, 0);
  EXPECT_GE(t.reached(), 145) << t.reached() << " of 150";
}

// The same at the region level (--level regions): the orientation regions crossed by the
// productions' headings, the viewframe level finishing. The same threshold and power as above.
TEST(QualnavSystem, RegionLevelGoalRateAtFiftyPercentRangeError) {
  const sim::World w = small_world();
  rig::QualnavSettings settings;
  settings.level = rig::QualnavLevel::regions;
  const rig::QualnavSystem system(w, settings);
  const auto plans = rig::draw_plans(system, w.objects.size(), 150, 21);
  rig::JourneySettings js;
  js.seed = 4;
  const rig::TrialsSummary t = rig::run_trials(system, plans, w, js, 0);
  EXPECT_GE(t.reached(), 145) << t.reached() << " of 150";
  std::printf("region level: %lld of 150 reached the goal\n", static_cast<long long>(t.reached()));
  int production_steps = 0;
  for (const rig::TrialRecord& r : t.trials) {
    const auto* report = std::any_cast<qn::NavigationReport>(&r.details);
    ASSERT_NE(report, nullptr);
    EXPECT_TRUE(report->regions.used);
    production_steps += report->regions.production_steps;
  }
  EXPECT_GT(production_steps, 150) << "the region level steers by the productions";
}

}  // namespace
