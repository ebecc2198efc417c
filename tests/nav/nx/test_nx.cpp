// NX in the dots world (qualnav.md §9, §10): the range ring, hill-climbing to the worked example's
// place, learned places against the true Voronoi vertices of OpenCV's subdivision (an independent
// computation), exploration's determinism, TOUR fed by NX, and journeys judged by the rig.

#include <gtest/gtest.h>

#include <cmath>

#include "nav/nx/controls.hpp"
#include "nav/nx/robot.hpp"
#include "rig/nx_system.hpp"
#include "rig/nx_voronoi.hpp"
#include "rig/station.hpp"
#include "rig/trials.hpp"
#include "sim/range_ring.hpp"

namespace neopipe {
namespace {

using Eigen::Vector2d;

sim::World world_of(std::vector<Vector2d> marbles, Vector2d size = {250, 250}) {
  sim::World w;
  w.size = size;
  w.marble_diameter = 5;
  w.objects = std::move(marbles);
  return w;
}

// The CLI tests' small world: ten marbles on 250 x 250 mm.
sim::World small_world() {
  return world_of({{30, 40},
                   {120, 30},
                   {210, 50},
                   {60, 120},
                   {150, 110},
                   {220, 150},
                   {40, 210},
                   {110, 190},
                   {190, 220},
                   {125, 145}});
}

rig::StationSettings exact_ring() {
  rig::StationSettings s;
  s.motion = rig::motion_errors(rig::ArmErrors{0, 0});
  sim::RangeRingSettings ring;
  ring.relative_error = 0;
  s.range_ring = ring;
  return s;
}

TEST(RangeRing, SectorsAndSurfaceRanges) {
  const sim::World w = world_of({{110, 100}, {100, 130}, {100, 300}});
  const auto r = sim::true_ranges(w, {100, 100, 0}, 150);
  EXPECT_DOUBLE_EQ(r[0], 7.5);   // east: 10 mm to the centre, 2.5 mm radius
  EXPECT_DOUBLE_EQ(r[4], 27.5);  // north, 90°
  EXPECT_EQ(std::count_if(r.begin(), r.end(), [](double x) { return x > 0; }), 2);  // (100, 300) out of reach
  const auto turned = sim::true_ranges(w, {100, 100, std::numbers::pi / 2}, 150);
  EXPECT_DOUBLE_EQ(turned[12], 7.5);  // the tool faces north: east is at −90°
  EXPECT_EQ(sim::range_sector(11.24), 0);
  EXPECT_EQ(sim::range_sector(11.26), 1);
  EXPECT_EQ(sim::range_sector(-11.24), 0);
  EXPECT_EQ(sim::range_sector(-11.26), 15);
}

TEST(RangeRing, ErrorStaysWithinItsBoundAndAveragesOut) {
  const sim::World w = world_of({{150, 100}});
  sim::RangeRingSettings s;
  s.relative_error = 0.10;
  sim::RangeRingSensor sensor(w, s);
  double sum = 0;
  constexpr int kFrames = 4000;
  for (int i = 0; i < kFrames; ++i) {
    const cv::Mat f = sensor.frame({100, 100, 0});
    ASSERT_EQ(f.type(), CV_32FC1);
    ASSERT_EQ(f.cols, 16);
    const double r = f.at<float>(0, 0);
    ASSERT_GE(r, 47.5 * 0.9 - 1e-4);
    ASSERT_LE(r, 47.5 * 1.1 + 1e-4);
    sum += r;
  }
  // Uniform ±10 %: sd 47.5 · 0.1 / √3 = 2.74 mm per frame, 0.043 mm for the mean; 5 sd.
  EXPECT_NEAR(sum / kFrames, 47.5, 0.22);
}

TEST(RangeRing, TheStationCarriesItWithACompass) {
  const sim::World w = small_world();
  rig::Station station(w, exact_ring(), {100, 100, 0});
  ASSERT_NE(station.compass(), nullptr);
  const auto f = station.camera().next();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->image.type(), CV_32FC1);
  EXPECT_THROW(station.onboard_camera(), std::logic_error);
}

// §10: marbles (0,0), (40,0), (0,30), noise off -> place (20,15) ± 1 mm (shifted by (100,100)).
TEST(NxPlaces, HillClimbingEndsOnTheWorkedExamplesPlace) {
  const sim::World w = world_of({{100, 100}, {140, 100}, {100, 130}});
  for (const Vector2d& start : {Vector2d(112, 108), Vector2d(126, 119), Vector2d(118, 106)}) {
    rig::Station station(w, exact_ring(), {start.x(), start.y(), 0.3});
    nav::nx::Robot robot(station.camera(), *station.compass(), station.arm(), rig::nx_config_for(0));
    const nav::nx::Climb climb = nav::nx::climb_to_place(robot);
    EXPECT_EQ(climb.ending, nav::nx::ClimbEnding::place);
    EXPECT_NEAR(station.tool().x, 120, 1) << start.transpose();
    EXPECT_NEAR(station.tool().y, 115, 1) << start.transpose();
  }
}

TEST(NxPlaces, TheReferenceVoronoiHasTheWorkedExamplesVertex) {
  const rig::VoronoiGraph g = rig::true_voronoi(world_of({{100, 100}, {140, 100}, {100, 130}}));
  ASSERT_EQ(g.vertices.size(), 1U);
  EXPECT_NEAR(g.vertices[0].x(), 120, 1e-3);
  EXPECT_NEAR(g.vertices[0].y(), 115, 1e-3);
}

rig::NxSettings exact_nx() {
  rig::NxSettings s;
  s.range_error = 0;
  s.arm = {0, 0};
  s.explore.max_places = 20;
  return s;
}

TEST(NxExploration, LearnedPlacesLieOnTheTrueVoronoiVertices) {
  const sim::World w = small_world();
  const rig::NxExploration e = rig::explore_world(w, exact_nx());
  const rig::VoronoiComparison c = rig::compare_with_voronoi(e, rig::true_voronoi(w), 2);
  ASSERT_GE(e.map.size(), 4U) << e.report.ending;
  for (const double err : c.place_errors) EXPECT_LE(err, 2.0);
  EXPECT_EQ(c.vertices_found, e.map.size());  // no two places on one vertex
  EXPECT_GE(c.edges_found, 3U);
  EXPECT_EQ(c.edges_wrong, 0U);
  EXPECT_EQ(e.report.ending, "agenda empty");
  // TOUR, fed by NX's stream, holds as many places as NX.
  EXPECT_EQ(e.tour_places, e.map.size());
}

TEST(NxExploration, SameSeedSameMap) {
  const sim::World w = small_world();
  rig::NxSettings s = exact_nx();
  s.range_error = 0.10;
  s.arm = {0.003, 0.002};
  s.explore.max_places = 6;
  const rig::NxExploration a = rig::explore_world(w, s);
  const rig::NxExploration b = rig::explore_world(w, s);
  ASSERT_EQ(a.map.size(), b.map.size());
  EXPECT_EQ(a.report.moves, b.report.moves);
  for (std::size_t i = 0; i < a.place_truth.size(); ++i) EXPECT_EQ(a.place_truth[i], b.place_truth[i]);
}

TEST(NxJourneys, ThroughTheRigReachTheGoalWithNoiseOff) {
  const sim::World w = small_world();
  const rig::NxSettings s = exact_nx();
  const rig::NxSystem system(w, rig::explore_world(w, s), s);
  const auto plans = rig::draw_plans(system, w.objects.size(), 12, 5);
  rig::JourneySettings js;
  js.errors = {0, 0};
  const rig::TrialsSummary t = rig::run_trials(system, plans, w, js, 2);
  EXPECT_EQ(t.reached(), t.run());
  for (const rig::TrialRecord& r : t.trials)
    EXPECT_TRUE(rig::reached_goal(r.outcome)) << r.from << " -> " << r.to << " " << r.reason;
}

TEST(NxJourneys, UnknownObjectsAndTooFewMarblesAreRefused) {
  const sim::World w = small_world();
  const rig::NxSettings s = exact_nx();
  const rig::NxSystem system(w, rig::explore_world(w, s), s);
  EXPECT_THROW((void)system.plan(0, 99), std::invalid_argument);
  EXPECT_THROW((void)system.plan(3, 3), std::invalid_argument);
  EXPECT_THROW((void)rig::explore_world(world_of({{10, 10}, {50, 50}}), s), std::invalid_argument);
}

}  // namespace
}  // namespace neopipe
