// The harness's outcome classification (park-kender.md §9) and the Wilson interval of its table.

#include <gtest/gtest.h>

#include "apps/nav_outcome.hpp"

namespace {
using neopipe::apps::classify;
using neopipe::apps::JourneyTruth;
using neopipe::apps::Outcome;
using neopipe::apps::wilson_interval;
using neopipe::nav::navigator::Ending;

TEST(NavOutcome, AwareFailuresComeFromTheNavigatorsEnding) {
  // Whatever the ground truth says, a navigator that stopped failed knowingly.
  EXPECT_EQ(classify({Ending::lost, 0, true, true}), Outcome::fail_lost);
  EXPECT_EQ(classify({Ending::lost, 2, false, false}), Outcome::fail_lost);
  EXPECT_EQ(classify({Ending::unrecoverable, 1, true, true}), Outcome::fail_unrecoverable);
  EXPECT_EQ(classify({Ending::unrecoverable, 0, false, false}), Outcome::fail_unrecoverable);
}

TEST(NavOutcome, ArrivalsAreJudgedByTheTruth) {
  EXPECT_EQ(classify({Ending::arrived, 0, true, true}), Outcome::success_direct);
  EXPECT_EQ(classify({Ending::arrived, 1, true, true}), Outcome::success_recovered);
  EXPECT_EQ(classify({Ending::arrived, 0, true, false}), Outcome::success_unaware);
  EXPECT_EQ(classify({Ending::arrived, 3, true, false}), Outcome::success_unaware);
  EXPECT_EQ(classify({Ending::arrived, 0, false, true}), Outcome::fail_unaware);
  EXPECT_EQ(classify({Ending::arrived, 2, false, false}), Outcome::fail_unaware);
}

TEST(NavOutcome, NamesAndGoalReached) {
  EXPECT_EQ(neopipe::apps::outcome_name(Outcome::success_recovered), "success_recovered");
  EXPECT_EQ(neopipe::apps::outcome_name(Outcome::fail_unaware), "fail_unaware");
  int reached = 0;
  for (const Outcome o : neopipe::apps::kOutcomes) reached += neopipe::apps::reached_goal(o) ? 1 : 0;
  EXPECT_EQ(reached, 3);
}

TEST(NavOutcome, WilsonIntervalMatchesKnownValues) {
  // 0 of 10: [0, 0.2775] (z = 1.96); 10 of 10 mirrors it; 50 of 100: 0.5 -+ 0.0962... -> [0.4038, 0.5962].
  const auto none = wilson_interval(0, 10);
  EXPECT_DOUBLE_EQ(none.low, 0.0);
  EXPECT_NEAR(none.high, 0.27753, 1e-4);
  const auto all = wilson_interval(10, 10);
  EXPECT_NEAR(all.low, 1 - 0.27753, 1e-4);
  EXPECT_DOUBLE_EQ(all.high, 1.0);
  const auto half = wilson_interval(50, 100);
  EXPECT_NEAR(half.low, 0.40383, 1e-4);
  EXPECT_NEAR(half.high, 0.59617, 1e-4);
  // 990 of 1000 (the sparse-world target): the interval excludes 0.98 and stays below 1.
  const auto target = wilson_interval(990, 1000);
  EXPECT_NEAR(target.low, 0.98170, 1e-4);
  EXPECT_NEAR(target.high, 0.99457, 1e-4);
  const auto empty = wilson_interval(0, 0);
  EXPECT_DOUBLE_EQ(empty.low, 0.0);
  EXPECT_DOUBLE_EQ(empty.high, 1.0);
}

}  // namespace
