// Another navigation system plugs into the same rig and is judged on the same worlds, pairs and
// outcomes: here the simplest one there is, a dead-reckoning baseline that moves the arm straight
// from the start's surveyed position to the goal's and claims the goal under the tool without
// looking. Its success hangs on the survey and the arm's errors alone.

#include <gtest/gtest.h>

#include <memory>

#include "dead_reckoning.hpp"
#include "rig/journey.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
using neopipe::test::DeadReckoning;

neopipe::sim::World world() {
  neopipe::sim::World w;
  w.size = {300, 300};
  w.objects = {{50, 50}, {250, 60}, {150, 250}, {60, 200}};
  return w;
}

TEST(OtherSystem, AnExactSurveyAndArmReachEveryGoal) {
  const auto w = world();
  const DeadReckoning system(w.objects);
  const auto plans = rig::draw_plans(system, w.objects.size(), 20, 1);
  rig::JourneySettings exact;
  exact.errors = {0, 0};
  const rig::TrialsSummary t = rig::run_trials(system, plans, w, exact, 2);
  EXPECT_EQ(t.count(rig::Outcome::success_direct), 20);
}

// The rig, not the system, decides: with a survey 6 mm off per axis (more than a marble's diameter
// for most objects) the claims land away from the goals and the rig says so, journey by journey, as
// unaware failures; the same journeys with the exact survey all succeed.
TEST(OtherSystem, TheRigJudgesItsClaimsAgainstTheTruth) {
  const auto w = world();
  const rig::Survey survey = rig::gaussian_survey(w, 6, 2);
  const DeadReckoning system(survey.workspace.objects);
  const auto plans = rig::draw_plans(system, w.objects.size(), 40, 1);
  rig::JourneySettings exact;
  exact.errors = {0, 0};
  const rig::TrialsSummary t = rig::run_trials(system, plans, w, exact, 2);
  EXPECT_GT(t.count(rig::Outcome::fail_unaware), 10);
  EXPECT_EQ(t.count(rig::Outcome::fail_unaware) + t.reached(), 40);

  // The same journeys with the exact survey, compared pair by pair.
  const DeadReckoning exact_system(w.objects);
  const rig::TrialsSummary u = rig::run_trials(exact_system, plans, w, exact, 1);
  const rig::PairedComparison c = rig::compare_paired(u, t);
  EXPECT_EQ(c.a_reached, 40);
  EXPECT_EQ(c.b_only, 0);
  EXPECT_EQ(c.a_only, 40 - t.reached());
  EXPECT_LT(c.p_value, 0.01);
}

TEST(OtherSystem, PairsTheSystemCannotPlanAreSkipped) {
  const auto w = world();
  const DeadReckoning system(w.objects, {.reach = 160});  // only pairs closer than 160 mm connect
  const auto plans = rig::draw_plans(system, w.objects.size(), 10, 3);
  for (const auto& p : plans) EXPECT_LE((w.objects[p->goal] - w.objects[p->start]).norm(), 160);
}

}  // namespace
