// Systems compared side by side (rig/comparison.hpp): the same pairs for every system, the pairs one
// system cannot plan dropped for all and counted, the McNemar test on the journeys where exactly one
// system reached the goal, path ratios against the straight line, and results independent of the
// thread count.

#include <gtest/gtest.h>

#include <memory>

#include "dead_reckoning.hpp"
#include "rig/comparison.hpp"
#include "rig/outcome.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
using neopipe::test::DeadReckoning;

neopipe::sim::World comparison_world() {
  neopipe::sim::World w;
  w.size = {300, 300};
  w.objects = {{50, 50}, {250, 60}, {150, 250}, {60, 200}, {200, 150}, {120, 110}};
  return w;
}

std::vector<rig::Contender> contenders(const neopipe::sim::World& w, double reach, bool second_gives_up) {
  std::vector<rig::Contender> c;
  c.push_back({std::make_unique<DeadReckoning>(w.objects), "a surveyed map"});
  c.push_back(
      {std::make_unique<DeadReckoning>(
           w.objects, neopipe::test::DeadReckoningOptions{.reach = reach, .gives_up_on_odd_goals = second_gives_up}),
       "the same map"});
  return c;
}

rig::ComparisonSettings exact_arm(std::int64_t trials, int threads) {
  rig::ComparisonSettings s;
  s.trials = trials;
  s.journey.errors = {0, 0};
  s.journey.seed = 7;
  s.threads = threads;
  return s;
}

TEST(Comparison, PairsOneSystemCannotPlanAreDroppedForAllAndCounted) {
  const auto w = comparison_world();
  const auto c = contenders(w, 160, false);
  const rig::CommonPlans common =
      rig::draw_common_plans({c[0].system.get(), c[1].system.get()}, w.objects.size(), 30, 5);
  ASSERT_EQ(common.pairs.size(), 30U);
  for (std::size_t i = 0; i < common.pairs.size(); ++i) {
    const auto [from, to] = common.pairs[i];
    EXPECT_LE((w.objects[to] - w.objects[from]).norm(), 160);
    for (const auto& plans : common.plans) {
      EXPECT_EQ(plans[i]->start, from);
      EXPECT_EQ(plans[i]->goal, to);
    }
  }
  EXPECT_EQ(common.unplanned[0], 0);
  EXPECT_GT(common.unplanned[1], 0);
  EXPECT_EQ(common.draws, 30 + common.unplanned[1]);
}

// With one system the comparison meets exactly the pairs rig::draw_plans draws for the same seed,
// so a comparison and `neopipe nav --trials` with one seed run the same journeys.
TEST(Comparison, OneSystemMeetsTheSamePairsAsItsOwnTrials) {
  const auto w = comparison_world();
  const DeadReckoning system(w.objects);
  const auto own = rig::draw_plans(system, w.objects.size(), 25, 11);
  const rig::CommonPlans common = rig::draw_common_plans({&system}, w.objects.size(), 25, 11);
  ASSERT_EQ(common.pairs.size(), own.size());
  for (std::size_t i = 0; i < own.size(); ++i) {
    EXPECT_EQ(common.pairs[i].first, own[i]->start);
    EXPECT_EQ(common.pairs[i].second, own[i]->goal);
  }
}

TEST(Comparison, McNemarCountsTheJourneysWhereExactlyOneSystemReachedTheGoal) {
  const auto w = comparison_world();
  const auto c = contenders(w, 1e9, true);
  const rig::Comparison r = rig::compare_systems(c, w, exact_arm(40, 2));
  ASSERT_EQ(r.results.size(), 2U);
  std::int64_t odd = 0;
  for (const auto& [from, to] : r.pairs) odd += to % 2;
  ASSERT_GT(odd, 5);
  EXPECT_EQ(r.results[0].summary.reached(), 40);
  EXPECT_EQ(r.results[1].summary.reached(), 40 - odd);
  EXPECT_EQ(r.results[1].summary.count(rig::Outcome::fail_lost), odd);
  ASSERT_EQ(r.tests.size(), 1U);
  EXPECT_EQ(r.tests[0].result.a_only, odd);
  EXPECT_EQ(r.tests[0].result.b_only, 0);
  EXPECT_DOUBLE_EQ(r.tests[0].result.p_value, rig::mcnemar_p(odd, 0));
}

// Travel over the straight line between the tool's ends: 1 for the straight mover, and for one that
// goes along x and then along y, the mean of (|dx| + |dy|) / |d| over its journeys.
TEST(Comparison, PathRatioIsTravelOverTheStraightLine) {
  const auto w = comparison_world();
  std::vector<rig::Contender> c;
  c.push_back({std::make_unique<DeadReckoning>(w.objects), "a surveyed map"});
  c.push_back({std::make_unique<DeadReckoning>(w.objects, neopipe::test::DeadReckoningOptions{.l_shaped = true}),
               "a surveyed map"});
  const rig::Comparison r = rig::compare_systems(c, w, exact_arm(20, 1));
  EXPECT_NEAR(r.results[0].mean_path_ratio, 1.0, 1e-9);
  EXPECT_NEAR(r.results[0].median_path_ratio, 1.0, 1e-9);
  double expected = 0;
  for (const auto& [from, to] : r.pairs) {
    const Eigen::Vector2d d = w.objects[to] - w.objects[from];
    expected += (std::abs(d.x()) + std::abs(d.y())) / d.norm();
  }
  EXPECT_NEAR(r.results[1].mean_path_ratio, expected / 20, 1e-9);
  EXPECT_GT(r.results[1].median_path_ratio, 1.05);
}

TEST(Comparison, ResultsDoNotDependOnTheThreadCount) {
  const auto w = comparison_world();
  const auto c = contenders(w, 160, true);
  rig::ComparisonSettings one = exact_arm(30, 1);
  one.journey.errors = {0.02, 0.01};
  rig::ComparisonSettings two = one;
  two.threads = 2;
  auto a = rig::comparison_json(rig::compare_systems(c, w, one));
  auto b = rig::comparison_json(rig::compare_systems(c, w, two));
  for (auto* j : {&a, &b}) {
    j->erase("seconds");
    for (auto& s : (*j)["systems"]) s.erase("seconds");
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["pairs"], 30);
  EXPECT_EQ(a["systems"][1]["unplanned"], a["draws"].get<std::int64_t>() - 30);
  for (const char* key : {"system", "knows", "journeys", "reached_goal", "reached_goal_rate", "reached_goal_ci95",
                          "outcomes", "path_ratio_mean", "path_ratio_median", "frames_mean"}) {
    EXPECT_TRUE(a["systems"][0].contains(key)) << key;
  }
  EXPECT_EQ(a["mcnemar"][0]["a"], "dead-reckoning");
}

}  // namespace
