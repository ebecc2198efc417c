// The experiment harness on the simulator: the map-maker's survey, the arm's reach, one journey
// judged against the truth, and trials that repeat by seed whatever the thread count.

#include <gtest/gtest.h>

#include "apps/nav_harness.hpp"
#include "apps/nav_survey.hpp"
#include "apps/nav_trials.hpp"
#include "sim/arm/scara.hpp"
#include "sim/world.hpp"

namespace {
namespace apps = neopipe::apps;
namespace mm = neopipe::nav::mapmaker;
using Eigen::Vector2d;

// Three marbles a step apart (0 -> 2 is one short step) and one far away that nothing reaches.
neopipe::sim::World small_world() {
  neopipe::sim::World w;
  w.size = {200, 200};
  w.objects = {{100, 100}, {125, 115}, {150, 140}, {40, 160}};
  return w;
}

mm::MapMakerOptions options(double sigma) {
  mm::MapMakerOptions o;
  o.window = neopipe::nav::WindowModel::with_side(50);
  o.errors.sigma = sigma;
  return o;
}

apps::JourneySettings exact_settings() {
  apps::JourneySettings s;
  s.errors = {0, 0};
  s.navigator.window = neopipe::nav::WindowModel::with_side(50);
  return s;
}

TEST(NavHarness, SurveyIsExactAtZeroSigmaAndSeededOtherwise) {
  const auto world = small_world();
  EXPECT_EQ(apps::gaussian_survey(world, 0, 3).workspace.objects, world.objects);
  const auto a = apps::gaussian_survey(world, 1, 3).workspace;
  EXPECT_EQ(apps::gaussian_survey(world, 1, 3).workspace.objects, a.objects);
  EXPECT_NE(apps::gaussian_survey(world, 1, 4).workspace.objects, a.objects);
  for (std::size_t i = 0; i < a.objects.size(); ++i) EXPECT_LT((a.objects[i] - world.objects[i]).norm(), 6.0);
  EXPECT_GT(apps::gaussian_survey(world, 1, 3).rms_error, 0);
}

// The rig's survey (global camera, engine, calibration) finds every marble of a default world under
// its own id, to the calibration's accuracy (docs/calibration.md: sd 0.005 mm per axis), and says
// how good it is from the calibration alone.
TEST(NavHarness, GlobalCameraSurveyFindsEveryMarbleToHundredthsOfAMillimetre) {
  neopipe::sim::WorldRequest q;
  q.objects = 100;
  q.seed = 1;
  const auto world = neopipe::sim::generate_world(q);
  const apps::Survey s = apps::global_camera_survey(world, 7);
  EXPECT_EQ(s.method, "global_camera");
  ASSERT_EQ(s.workspace.objects.size(), world.objects.size());
  EXPECT_LT(s.rms_error, 0.03);
  EXPECT_LT(s.max_error, 0.1);
  EXPECT_GT(s.rms_error, 0);  // a real measurement, not the truth handed over
  EXPECT_GT(s.sigma, 0);
  EXPECT_LT(s.sigma, 0.03);
  EXPECT_EQ(apps::global_camera_survey(world, 7).workspace.objects, s.workspace.objects);
}

TEST(NavHarness, GlobalCameraSurveyRefusesMarblesItCannotTellApart) {
  neopipe::sim::World w;
  w.size = {500, 500};
  w.objects = {{100, 100}, {105, 100}, {300, 300}};  // the first two touch
  EXPECT_THROW(apps::global_camera_survey(w, 1), mm::MapError);
}

TEST(NavHarness, ArmReachesOneWindowBeyondTheWorld) {
  const auto world = small_world();
  const neopipe::sim::Scara arm(apps::arm_for_world(world, 50));
  for (const Vector2d& p :
       {Vector2d(-50, -50), Vector2d(250, -50), Vector2d(-50, 250), Vector2d(250, 250), Vector2d(100, 100)}) {
    for (const double theta : {0.0, 1.0, -2.5}) EXPECT_TRUE(arm.reachable({p.x(), p.y(), theta})) << p.transpose();
  }
}

TEST(NavHarness, ErrorFreeJourneyIsADirectSuccessAndTheTruthIsChecked) {
  const auto world = small_world();
  const mm::MapMaker maker(apps::gaussian_survey(world, 0, 1).workspace, options(0));
  mm::Route route = maker.plan(0, 2, mm::CostCriterion::ratio);
  const apps::JourneyResult r = apps::run_journey(world, route, exact_settings());
  EXPECT_EQ(r.outcome, apps::Outcome::success_direct) << r.report.reason;
  ASSERT_FALSE(r.held.empty());
  EXPECT_EQ(r.held.back().actual, 2U);
  EXPECT_TRUE(r.held.back().correct);
  EXPECT_GT(r.frames, 0);
  EXPECT_NEAR(r.true_travel, r.commanded_travel, 1e-6);
  EXPECT_GE(r.track.size(), 1U);

  // The same journey judged against a different goal: the navigator still arrives where the map
  // leads, believes it succeeded, and the harness calls it an unaware failure.
  route.goal = 1;
  route.steps.back().step.landmark = 1;
  EXPECT_EQ(apps::run_journey(world, route, exact_settings()).outcome, apps::Outcome::fail_unaware);
}

TEST(NavHarness, TrialsRepeatBySeedForAnyThreadCount) {
  const auto world = small_world();
  const mm::MapMaker maker(apps::gaussian_survey(world, 0.5, 2).workspace, options(0.5));
  const auto routes = apps::draw_routes(maker, mm::CostCriterion::ratio, 6, 11);
  ASSERT_EQ(routes.size(), 6U);
  for (const mm::Route& r : routes) {
    EXPECT_NE(r.start, r.goal);
    EXPECT_NE(r.start, 3U);  // object 3 is cut off from the others
    EXPECT_NE(r.goal, 3U);
  }
  apps::JourneySettings s = exact_settings();
  s.errors = {0.003, 0.002};
  s.seed = 5;
  const auto one = apps::run_trials(world, routes, s, 1);
  const auto two = apps::run_trials(world, routes, s, 2);
  ASSERT_EQ(one.trials.size(), 6U);
  EXPECT_EQ(one.counts, two.counts);
  EXPECT_EQ(one.frames, two.frames);
  EXPECT_EQ(one.true_travel, two.true_travel);
  std::int64_t total = 0;
  for (const auto c : one.counts) total += c;
  EXPECT_EQ(total, 6);
  EXPECT_NE(apps::trial_seed(5, 0), apps::trial_seed(5, 1));

  // Two marbles that never share a window and have no direction to slide along: no pair connects,
  // and drawing ends with an error instead of looping.
  neopipe::sim::World apart;
  apart.size = {200, 200};
  apart.objects = {{20, 20}, {180, 180}};
  const mm::MapMaker lonely(apps::gaussian_survey(apart, 0, 1).workspace, options(0));
  EXPECT_THROW(apps::draw_routes(lonely, mm::CostCriterion::ratio, 1, 1), mm::MapError);
}

}  // namespace
