// QRM's system in the rig (rig/qrm_system.hpp): the map built by an imaging tour, plans on it,
// journeys through the station's panoramic sensor and arm judged against the truth, the trials JSON
// the same for one thread and two, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <vector>

#include "nav/qrm/rng.hpp"
#include "rig/journey.hpp"
#include "rig/qrm_system.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace {

namespace rig = neopipe::rig;
namespace q = neopipe::nav::qrm;
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

rig::QrmSettings settings() {
  rig::QrmSettings s;
  s.images = 8;
  s.seed = 3;
  return s;
}

TEST(QrmSystem, TheTourBuildsAMapWhoseRngHoldsTheTrueOne) {
  const sim::World w = small_world();
  rig::ImagingTour tour;
  const q::RelationalMap map = rig::build_map_by_tour(w, settings(), &tour);
  EXPECT_EQ(tour.images, 8U);
  EXPECT_GT(tour.triples, 0U);
  EXPECT_EQ(map.size(), w.objects.size());
  // The map never loses a true state, so no true RNG edge is pruned.
  const auto truth = q::true_rng(w.objects);
  const q::RngEstimate estimate = q::estimate_rng(map);
  for (const auto& edge : truth) {
    const auto [i, j] = edge;
    EXPECT_TRUE(std::any_of(estimate.edges.begin(), estimate.edges.end(),
                            [&](const q::RngEdge& e) { return e.i == edge.first && e.j == edge.second; }))
        << i << "-" << j;
  }
}

TEST(QrmSystem, JourneysReachTheirGoalsKeepingClearOfTheMarbles) {
  const sim::World w = small_world();
  const rig::QrmSystem system(w, rig::build_map_by_tour(w, settings()), settings());
  EXPECT_EQ(system.name(), "qrm");
  EXPECT_EQ(system.camera().sensor, rig::Sensor::panoramic);
  const auto plans = rig::draw_plans(system, w.objects.size(), 6, 11);
  for (const auto& plan : plans) {
    EXPECT_EQ(plan->landmarks, (std::vector<std::uint32_t>{plan->start, plan->goal}));
    const auto& route = rig::qrm_route(*plan);
    ASSERT_GE(route.size(), 2U);
    EXPECT_EQ(route.front(), plan->start);
    EXPECT_EQ(route.back(), plan->goal);
    // The start: in the start marble's cell, 12.5 mm or more from every centre.
    const Vector2d at = w.objects[plan->start] + plan->start_offset;
    for (std::size_t i = 0; i < w.objects.size(); ++i) {
      EXPECT_GE((w.objects[i] - at).norm(), 12.5);
      if (i != plan->start) {
        EXPECT_LT(plan->start_offset.norm(), (w.objects[i] - at).norm());
      }
    }
    rig::JourneySettings js;
    js.seed = 7;
    const rig::JourneyResult r = rig::run_journey(system, *plan, w, js);
    EXPECT_TRUE(rig::reached_goal(r.outcome)) << plan->start << " -> " << plan->goal << ": " << r.travel.reason;
    const q::NavigationReport* report = rig::qrm_report(r.travel);
    ASSERT_NE(report, nullptr);
    EXPECT_EQ(report->reached.back(), plan->goal);
    ASSERT_FALSE(r.held.empty());
    EXPECT_EQ(r.held.back().entry, 1U);
    EXPECT_TRUE(r.held.back().correct);
    // Direct unless the navigator left the planned route (a re-route, its recovery).
    EXPECT_EQ(r.outcome, report->reroutes > 0 ? rig::Outcome::success_recovered : rig::Outcome::success_direct);
    // The robot keeps 10 mm from every marble's surface all the way (qualnav.md §2).
    for (const Vector2d& p : r.arm.track) {
      for (const Vector2d& m : w.objects) EXPECT_GE((m - p).norm(), 12.5);
    }
  }
}

TEST(QrmSystem, TrialsAreTheSameOnOneThreadAndTwo) {
  const sim::World w = small_world();
  const rig::QrmSystem system(w, rig::build_map_by_tour(w, settings()), settings());
  const auto plans = rig::draw_plans(system, w.objects.size(), 4, 5);
  rig::JourneySettings js;
  js.seed = 9;
  const rig::TrialsSummary one = rig::run_trials(system, plans, w, js, 1);
  const rig::TrialsSummary two = rig::run_trials(system, plans, w, js, 2);
  auto a = rig::qrm_trials_json(system, plans, one);
  auto b = rig::qrm_trials_json(system, plans, two);
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["trials"], 4);
  EXPECT_EQ(a["reached_goal"].get<int>() + a["outcomes"]["fail_lost"].get<int>() +
                a["outcomes"]["fail_unrecoverable"].get<int>() + a["outcomes"]["fail_unaware"].get<int>(),
            4);
  EXPECT_TRUE(a["qrm"]["endings"].contains("target_lost"));
}

TEST(QrmSystem, BadInput) {
  sim::World two;
  two.objects = {{50, 50}, {100, 100}};
  EXPECT_THROW((void)rig::build_map_by_tour(two, settings()), std::invalid_argument);
  EXPECT_THROW(rig::QrmSystem(two, q::RelationalMap{}, settings()), std::invalid_argument);
  const sim::World w = small_world();
  const rig::QrmSystem system(w, rig::build_map_by_tour(w, settings()), settings());
  EXPECT_THROW((void)system.plan(0, 10), std::invalid_argument);
  EXPECT_THROW((void)system.plan(3, 3), std::invalid_argument);
  // A landmark the tour never saw cannot be planned to.
  const rig::QrmSystem blind(w, q::RelationalMap{}, settings());
  EXPECT_THROW((void)blind.plan(0, 1), rig::UnreachableGoal);
}

}  // namespace
