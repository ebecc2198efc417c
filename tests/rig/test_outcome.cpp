// The rig's outcome classification (park-kender.md §9), the Wilson interval of its table and the
// McNemar test of paired runs.

#include <gtest/gtest.h>

#include <cmath>

#include "rig/outcome.hpp"

namespace {
using neopipe::rig::classify;
using neopipe::rig::Ending;
using neopipe::rig::JourneyTruth;
using neopipe::rig::mcnemar_p;
using neopipe::rig::Outcome;
using neopipe::rig::wilson_interval;

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
  EXPECT_EQ(neopipe::rig::outcome_name(Outcome::success_recovered), "success_recovered");
  EXPECT_EQ(neopipe::rig::outcome_name(Outcome::fail_unaware), "fail_unaware");
  int reached = 0;
  for (const Outcome o : neopipe::rig::kOutcomes) reached += neopipe::rig::reached_goal(o) ? 1 : 0;
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

// Exact two-sided sign test: values worked by hand from the binomial distribution.
TEST(NavOutcome, McNemarIsTheExactSignTest) {
  EXPECT_DOUBLE_EQ(mcnemar_p(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(mcnemar_p(3, 3), 1.0);
  EXPECT_NEAR(mcnemar_p(7, 0), 2.0 / 128, 1e-12);                // 2 * 0.5^7
  EXPECT_NEAR(mcnemar_p(0, 7), 2.0 / 128, 1e-12);                // symmetric
  EXPECT_NEAR(mcnemar_p(4, 0), 0.125, 1e-12);                    // 2 * 0.5^4
  EXPECT_NEAR(mcnemar_p(14, 5), 2 * 0.0317840576171875, 1e-12);  // 2 P(X <= 5), X ~ B(19, 1/2)
  EXPECT_NEAR(mcnemar_p(1, 2), 1.0, 1e-12);                      // 2 * 0.5 capped at 1
  // Thousands of discordant journeys neither overflow nor lose the tail.
  EXPECT_NEAR(mcnemar_p(1100, 900), 8.457089535503927e-06, 1e-12);
}

}  // namespace
