// The rig on the simulator: the map-maker's survey, the arm's reach, one journey judged against the
// truth, trials that repeat by seed whatever the thread count, paired comparisons, and the
// experiment settings the command line uses.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "rig/experiment.hpp"
#include "rig/journey.hpp"
#include "rig/park_kender.hpp"
#include "rig/seeds.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/arm/scara.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
namespace mm = neopipe::nav::mapmaker;
using Eigen::Vector2d;

// Three marbles a step apart (0 -> 2 is one short step) and one far away that nothing reaches.
neopipe::sim::World small_world() {
  neopipe::sim::World w;
  w.size = {200, 200};
  w.objects = {{100, 100}, {125, 115}, {150, 140}, {40, 160}};
  return w;
}

// Park & Kender's system on a survey, the navigator's window the map-maker's.
std::unique_ptr<rig::ParkKenderSystem> system_on(const mm::Workspace& survey, double sigma,
                                                 mm::CostCriterion criterion = mm::CostCriterion::ratio) {
  mm::MapMakerOptions o;
  o.window = neopipe::nav::WindowModel::with_side(50);
  o.errors.sigma = sigma;
  neopipe::nav::navigator::NavigatorConfig n;
  n.window = o.window;
  return std::make_unique<rig::ParkKenderSystem>(survey, o, criterion, n);
}

rig::JourneySettings exact_settings() {
  rig::JourneySettings s;
  s.errors = {0, 0};
  return s;
}

TEST(Rig, SurveyIsExactAtZeroSigmaAndSeededOtherwise) {
  const auto world = small_world();
  EXPECT_EQ(rig::gaussian_survey(world, 0, 3).workspace.objects, world.objects);
  const auto a = rig::gaussian_survey(world, 1, 3).workspace;
  EXPECT_EQ(rig::gaussian_survey(world, 1, 3).workspace.objects, a.objects);
  EXPECT_NE(rig::gaussian_survey(world, 1, 4).workspace.objects, a.objects);
  for (std::size_t i = 0; i < a.objects.size(); ++i) EXPECT_LT((a.objects[i] - world.objects[i]).norm(), 6.0);
  EXPECT_GT(rig::gaussian_survey(world, 1, 3).rms_error, 0);
}

TEST(Rig, ArmReachesOneWindowBeyondTheWorld) {
  const auto world = small_world();
  const neopipe::sim::Scara arm(rig::arm_for_world(world, 50));
  for (const Vector2d& p :
       {Vector2d(-50, -50), Vector2d(250, -50), Vector2d(-50, 250), Vector2d(250, 250), Vector2d(100, 100)}) {
    for (const double theta : {0.0, 1.0, -2.5}) EXPECT_TRUE(arm.reachable({p.x(), p.y(), theta})) << p.transpose();
  }
}

TEST(Rig, ErrorFreeJourneyIsADirectSuccessAndTheTruthIsChecked) {
  const auto world = small_world();
  const auto system = system_on(rig::gaussian_survey(world, 0, 1).workspace, 0);
  const auto plan = system->plan(0, 2);
  EXPECT_EQ(plan->landmarks.front(), 0U);
  EXPECT_EQ(plan->landmarks.back(), 2U);
  const rig::JourneyResult r = rig::run_journey(*system, *plan, world, exact_settings());
  EXPECT_EQ(r.outcome, rig::Outcome::success_direct) << r.travel.reason;
  ASSERT_FALSE(r.held.empty());
  EXPECT_EQ(r.held.back().actual, 2U);
  EXPECT_TRUE(r.held.back().correct);
  EXPECT_GT(r.frames, 0);
  EXPECT_NEAR(r.arm.true_travel, r.arm.commanded_travel, 1e-6);
  EXPECT_GE(r.arm.track.size(), 1U);
  ASSERT_NE(rig::navigator_report(r.travel), nullptr);
  EXPECT_EQ(rig::navigator_report(r.travel)->frames, r.frames);

  // The same journey judged against a different goal: the navigator still arrives where the map
  // leads, believes it succeeded, and the rig calls it an unaware failure.
  auto wrong = std::make_unique<rig::ParkKenderPlan>(dynamic_cast<const rig::ParkKenderPlan&>(*plan));
  wrong->goal = 1;
  wrong->landmarks.back() = 1;
  EXPECT_EQ(rig::run_journey(*system, *wrong, world, exact_settings()).outcome, rig::Outcome::fail_unaware);
}

TEST(Rig, UnreachableGoalIsTheRigsError) {
  const auto world = small_world();
  const auto system = system_on(rig::gaussian_survey(world, 0, 1).workspace, 0);
  EXPECT_THROW((void)system->plan(0, 3), rig::UnreachableGoal);
}

TEST(Rig, TrialsRepeatBySeedForAnyThreadCount) {
  const auto world = small_world();
  const auto system = system_on(rig::gaussian_survey(world, 0.5, 2).workspace, 0.5);
  const auto plans = rig::draw_plans(*system, world.objects.size(), 6, 11);
  ASSERT_EQ(plans.size(), 6U);
  for (const auto& p : plans) {
    EXPECT_NE(p->start, p->goal);
    EXPECT_NE(p->start, 3U);  // object 3 is cut off from the others
    EXPECT_NE(p->goal, 3U);
  }
  rig::JourneySettings s = exact_settings();
  s.errors = {0.003, 0.002};
  s.seed = 5;
  const auto one = rig::run_trials(*system, plans, world, s, 1);
  const auto two = rig::run_trials(*system, plans, world, s, 2);
  ASSERT_EQ(one.trials.size(), 6U);
  EXPECT_EQ(one.counts, two.counts);
  EXPECT_EQ(one.frames, two.frames);
  EXPECT_EQ(one.true_travel, two.true_travel);
  std::int64_t total = 0;
  for (const auto c : one.counts) total += c;
  EXPECT_EQ(total, 6);
  EXPECT_NE(rig::trial_seed(5, 0), rig::trial_seed(5, 1));

  // Two marbles that never share a window and have no direction to slide along: no pair connects,
  // and drawing ends with an error instead of looping.
  neopipe::sim::World apart;
  apart.size = {200, 200};
  apart.objects = {{20, 20}, {180, 180}};
  const auto lonely = system_on(rig::gaussian_survey(apart, 0, 1).workspace, 0);
  EXPECT_THROW(rig::draw_plans(*lonely, apart.objects.size(), 1, 1), std::runtime_error);
}

TEST(Rig, PairedComparisonCountsDiscordantJourneys) {
  rig::TrialsSummary a;
  rig::TrialsSummary b;
  const auto add = [](rig::TrialsSummary& t, std::uint32_t from, rig::Outcome o) {
    rig::TrialRecord r;
    r.from = from;
    r.to = from + 1;
    r.outcome = o;
    t.trials.push_back(r);
  };
  using O = rig::Outcome;
  // 0: both reach; 1, 2: only a; 3: only b; 4: neither.
  for (const auto& [x, y] : {std::pair{O::success_direct, O::success_recovered},
                             {O::success_unaware, O::fail_lost},
                             {O::success_direct, O::fail_unaware},
                             {O::fail_unrecoverable, O::success_direct},
                             {O::fail_lost, O::fail_unaware}}) {
    add(a, static_cast<std::uint32_t>(a.trials.size()), x);
    add(b, static_cast<std::uint32_t>(b.trials.size()), y);
  }
  const rig::PairedComparison c = rig::compare_paired(a, b);
  EXPECT_EQ(c.journeys, 5);
  EXPECT_EQ(c.a_reached, 3);
  EXPECT_EQ(c.b_reached, 2);
  EXPECT_EQ(c.a_only, 2);
  EXPECT_EQ(c.b_only, 1);
  EXPECT_DOUBLE_EQ(c.p_value, rig::mcnemar_p(2, 1));
  b.trials[2].from = 9;  // not the same journeys
  EXPECT_THROW(rig::compare_paired(a, b), std::invalid_argument);
  b.trials.pop_back();
  EXPECT_THROW(rig::compare_paired(a, b), std::invalid_argument);
}

// The settings `neopipe nav` derives: the map-maker rates steps with the survey's told error and
// the navigator's own placement error; the border band and the navigator's view margin are one.
TEST(Rig, ExperimentSettingsComeFromTheSurveyAndTheArm) {
  rig::ExperimentConfig c;
  c.window = 40;
  c.arm = {0.004, 0.003};
  c.recovery = false;
  c.seed = 9;
  const rig::ExperimentSettings s = rig::derive_settings(c, 1.0);
  c.extended_descriptions = false;
  EXPECT_FALSE(rig::derive_settings(c, 1.0).map.extended_descriptions);
  EXPECT_EQ(s.map.window.side, 40);
  EXPECT_EQ(s.navigator.window.side, 40);
  EXPECT_NEAR(s.map.errors.sigma, std::hypot(1.0, 0.2), 1e-12);
  // 3 sd of two objects' relative survey error, the navigator's border error and its adjust tolerance
  EXPECT_NEAR(s.map.border_tolerance, 3 * std::sqrt(2.0) + rig::kNavigatorBorderError + 0.4, 1e-12);
  EXPECT_EQ(s.navigator.view_margin, s.map.border_tolerance);
  EXPECT_TRUE(s.map.extended_descriptions);
  EXPECT_FALSE(s.navigator.recovery);
  EXPECT_EQ(s.journey.errors.sigma_move, 0.004);
  EXPECT_EQ(s.journey.seed, 9U);
  c.window = -1;
  EXPECT_THROW(rig::derive_settings(c, 1.0), std::invalid_argument);
  c.window = 50;
  c.arm.sigma_rot = -1;
  EXPECT_THROW(rig::derive_settings(c, 1.0), std::invalid_argument);
  c.arm.sigma_rot = 0;
  EXPECT_THROW(rig::derive_settings(c, std::nan("")), std::invalid_argument);
}

// 40 marbles in 250 x 250 mm: the default density on a world small enough for quick trials.
neopipe::sim::World small_default_density_world() {
  neopipe::sim::WorldRequest q;
  q.objects = 40;
  q.size = {250, 250};
  q.seed = 4;
  return neopipe::sim::generate_world(q);
}

// What `neopipe nav --trials N --seed 3` sets up on that world with a Gaussian survey.
struct SmallTrials {
  neopipe::sim::World world = small_default_density_world();
  rig::Survey survey;
  rig::ExperimentSettings settings;
  std::unique_ptr<rig::ParkKenderSystem> system;
  std::vector<std::unique_ptr<rig::Plan>> plans;

  SmallTrials(double survey_sigma, mm::CostCriterion criterion, std::int64_t count, double min_reliability = 0)
      : survey(rig::gaussian_survey(world, survey_sigma, 3)) {
    rig::ExperimentConfig c;
    c.seed = 3;
    c.min_reliability = min_reliability;
    settings = rig::derive_settings(c, survey.sigma);
    system = rig::make_park_kender(survey, settings, criterion);
    plans = rig::draw_plans(*system, world.objects.size(), count, c.seed);
  }
  rig::TrialsSummary run(int threads) const {
    return rig::run_trials(*system, plans, world, settings.journey, threads);
  }
};

// The path behind `neopipe nav --trials` (survey, settings, system, draws, trials), here on a small
// default-density world: every journey is judged, most arrive, and the run repeats exactly.
TEST(Rig, PublishedTrialsPathRunsThroughTheLibrary) {
  const SmallTrials small(0.05, mm::CostCriterion::reliability, 12);
  const rig::TrialsSummary t = small.run(2);
  ASSERT_EQ(t.trials.size(), 12U);
  EXPECT_GE(t.reached(), 10);
  EXPECT_GT(t.mean_planned_reliability(), 0.5);
  EXPECT_GT(t.frames, 12 * 5);
  const rig::TrialsSummary again = small.run(1);
  EXPECT_EQ(again.counts, t.counts);
  EXPECT_EQ(again.frames, t.frames);
}

// --min-reliability: routes forecast below it are refused, not run, and counted apart; the rest
// are the very journeys of a run without it (same pairs, same noise).
TEST(Rig, RoutesForecastBelowTheLeastReliabilityAreRefusedAndCountedApart) {
  const SmallTrials free(1.5, mm::CostCriterion::ratio, 16);
  const SmallTrials strict(1.5, mm::CostCriterion::ratio, 16, 0.97);
  const auto& free_plans = free.plans;
  const auto& strict_plans = strict.plans;
  ASSERT_EQ(strict_plans.size(), free_plans.size());
  int refused = 0;
  for (std::size_t i = 0; i < strict_plans.size(); ++i) {
    const rig::Plan& p = *strict_plans[i];
    EXPECT_EQ(p.start, free_plans[i]->start);
    if (!p.refused.empty()) {
      ++refused;
      EXPECT_LT(p.planned_reliability, 0.97);
      EXPECT_NE(p.refused.find("reliable enough"), std::string::npos) << p.refused;
    } else {
      EXPECT_GE(p.planned_reliability, 0.97);  // the criterion's route, or else the most reliable one
    }
  }
  ASSERT_GT(refused, 0) << "the test needs routes below the level";
  ASSERT_LT(refused, 16);
  const rig::TrialsSummary t = strict.run(2);
  EXPECT_EQ(t.refused, refused);
  EXPECT_EQ(t.run(), 16 - refused);
  std::int64_t counted = 0;
  for (const std::int64_t n : t.counts) counted += n;
  EXPECT_EQ(counted, t.run());  // a refusal is no outcome, not a failure
  for (const rig::TrialRecord& r : t.trials) {
    if (r.refused) {
      EXPECT_EQ(r.frames, 0);
    }
  }
  rig::ExperimentConfig c;
  c.min_reliability = 1.5;
  EXPECT_THROW((void)rig::derive_settings(c, 1.5), std::invalid_argument);
}

}  // namespace
