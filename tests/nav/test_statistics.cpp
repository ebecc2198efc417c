// Parkway statistics: counts on hand-made worlds, determinism across thread counts, confidence
// intervals, and the paper's Poisson estimate against simulation.

#include <gtest/gtest.h>

#include <cmath>

#include "nav/mapmaker/statistics.hpp"

namespace {

namespace mm = neopipe::nav::mapmaker;
using Eigen::Vector2d;

// Window 10, margin 0.5: two objects share a window when |dx|, |dy| < 9. Two pairs on one line, 25 mm
// apart (two general parkways), and a lone object far off. Held at SW/NW, A sees only B; held at SE/NE,
// B sees only A; likewise C, D. Sliding from B away from A (Trajn) meets C first, and from C away
// from D meets B: trajectories join the pairs both ways; nothing ever slides past E.
mm::Workspace two_pairs_and_a_loner() {
  return {{100, 100}, {{10, 10}, {15, 10}, {40, 10}, {45, 10}, {80, 80}}};
}

TEST(ParkwayStatistics, HandMadeWorldCounts) {
  const neopipe::nav::WindowModel window{10, 0.5};
  const mm::WorldCounts c = mm::measure_world(two_pairs_and_a_loner(), window);
  EXPECT_EQ(c.general_parkways, 3);
  EXPECT_EQ(c.multi_object_parkways, 2);
  EXPECT_EQ(c.isolated_objects, 1);
  EXPECT_EQ(c.obvious_edges, 8);   // two corners per object of a pair
  EXPECT_EQ(c.isolated_edges, 8);  // one other object in view: the same landmark
  EXPECT_EQ(c.obvious_parkways, 3);
  EXPECT_EQ(c.isolated_parkways, 3);      // {A, B}, {C, D}, {E}
  EXPECT_EQ(c.scc_with_trajectories, 2);  // {A, B, C, D}, {E}
  EXPECT_GT(c.trajectories, 0);
  EXPECT_EQ(c.new_parkways, 3);  // A, C and E found one; B and D join
}

TEST(ParkwayStatistics, EmptyAndSingleObjectWorlds) {
  const neopipe::nav::WindowModel window{10, 0.5};
  const mm::WorldCounts none = mm::measure_world({{100, 100}, {}}, window);
  EXPECT_EQ(none.general_parkways, 0);
  EXPECT_EQ(none.scc_with_trajectories, 0);
  const mm::WorldCounts one = mm::measure_world({{100, 100}, {{50, 50}}}, window);
  EXPECT_EQ(one.general_parkways, 1);
  EXPECT_EQ(one.isolated_objects, 1);
  EXPECT_EQ(one.isolated_parkways, 1);
  EXPECT_EQ(one.new_parkways, 1);
}

TEST(ParkwayStatistics, NewParkwaysDependOnTheOrderOfArrival) {
  const neopipe::nav::WindowModel window{10, 0.5};
  // B between A and C joins them, but only if it comes last: then A and C each founded one.
  const std::vector<Vector2d> a_c_b{{10, 10}, {26, 10}, {18, 10}};
  const std::vector<Vector2d> a_b_c{{10, 10}, {18, 10}, {26, 10}};
  EXPECT_EQ(mm::count_new_parkways(a_c_b, window), 2U);
  EXPECT_EQ(mm::count_new_parkways(a_b_c, window), 1U);
}

TEST(ParkwayStatistics, NewParkwaysAgreeWithBruteForce) {
  for (const double side : {2.0, 5.0, 10.0}) {
    const neopipe::nav::WindowModel window = neopipe::nav::WindowModel::with_side(side);
    for (std::size_t trial = 0; trial < 5; ++trial) {
      const auto objects = mm::random_objects(100, 3, trial, 300);
      std::size_t brute = 0;
      for (std::size_t j = 0; j < objects.size(); ++j) {
        bool seen = false;
        for (std::size_t i = 0; i < j; ++i) seen = seen || window.fit_together(objects[i], objects[j]);
        if (!seen) ++brute;
      }
      EXPECT_EQ(mm::count_new_parkways(objects, window), brute) << side << " " << trial;
    }
  }
}

TEST(ParkwayStatistics, RandomWorldsAreNestedAndInside) {
  const auto small = mm::random_objects(100, 7, 3, 50);
  const auto large = mm::random_objects(100, 7, 3, 200);
  ASSERT_EQ(small.size(), 50U);
  for (std::size_t i = 0; i < small.size(); ++i) EXPECT_EQ(small[i], large[i]);
  for (const Vector2d& p : large) {
    EXPECT_GT(p.minCoeff(), 0);
    EXPECT_LT(p.maxCoeff(), 100);
  }
  EXPECT_NE(mm::random_objects(100, 7, 4, 1)[0], small[0]);  // another trial, another world
  EXPECT_NE(mm::random_objects(100, 8, 3, 1)[0], small[0]);  // another seed too
}

TEST(ParkwayStatistics, SummaryIsAStudentTInterval) {
  const mm::Summary s = mm::summarise({1, 2, 3, 4, 5});
  EXPECT_DOUBLE_EQ(s.mean, 3);
  EXPECT_NEAR(s.sd, std::sqrt(2.5), 1e-12);
  const double half = 2.776 * std::sqrt(2.5) / std::sqrt(5.0);
  EXPECT_NEAR(s.ci_low, 3 - half, 1e-9);
  EXPECT_NEAR(s.ci_high, 3 + half, 1e-9);
  EXPECT_NEAR(mm::t_quantile_975(30), 2.042, 1e-3);
  EXPECT_NEAR(mm::t_quantile_975(31), 2.040, 1e-3);
  EXPECT_NEAR(mm::t_quantile_975(60), 2.000, 1e-3);
  EXPECT_NEAR(mm::t_quantile_975(1000000), 1.960, 1e-3);
  const mm::Summary one = mm::summarise({4});
  EXPECT_EQ(one.sd, 0);
  EXPECT_EQ(one.ci_low, 4);
}

mm::StatisticsOptions small_run() {
  mm::StatisticsOptions o;
  o.size = 60;
  o.windows = {4, 7};
  o.populations = {0, 30, 90};
  o.trials = 6;
  o.seed = 11;
  return o;
}

TEST(ParkwayStatistics, SameResultsForEveryThreadCount) {
  mm::StatisticsOptions o = small_run();
  o.threads = 1;
  const auto one = mm::parkway_statistics(o);
  for (const int threads : {2, 4}) {
    o.threads = threads;
    const auto many = mm::parkway_statistics(o);
    ASSERT_EQ(many.size(), one.size());
    for (std::size_t r = 0; r < one.size(); ++r) {
      EXPECT_EQ(many[r].window.side, one[r].window.side);
      EXPECT_EQ(many[r].population, one[r].population);
      for (std::size_t f = 0; f < mm::kCountFields; ++f) {
        // Bit for bit: the reduction is in a fixed order.
        EXPECT_EQ(many[r].counts[f].mean, one[r].counts[f].mean) << r << " " << mm::count_names()[f];
        EXPECT_EQ(many[r].counts[f].sd, one[r].counts[f].sd) << r << " " << mm::count_names()[f];
      }
    }
  }
}

TEST(ParkwayStatistics, RowsInOrderWithProgress) {
  std::size_t calls = 0;
  std::size_t last = 0;
  const auto rows = mm::parkway_statistics(small_run(), [&](std::size_t done, std::size_t total) {
    ++calls;
    EXPECT_EQ(total, 2U * 3U * 6U);
    last = std::max(last, done);
  });
  EXPECT_EQ(calls, 36U);
  EXPECT_EQ(last, 36U);
  ASSERT_EQ(rows.size(), 6U);
  EXPECT_EQ(rows[0].window.side, 4);
  EXPECT_DOUBLE_EQ(rows[0].window.margin, 0.2);
  EXPECT_EQ(rows[2].population, 90U);
  EXPECT_EQ(rows[3].window.side, 7);
  EXPECT_EQ(rows[0].counts[0].mean, 0);  // population 0
  for (const auto& r : rows) {
    // general >= multi-object parkways; SCCs: obvious >= isolated >= with trajectories.
    EXPECT_LE(r.counts[1].mean, r.counts[0].mean);
    EXPECT_GE(r.counts[3].mean, r.counts[4].mean);
    EXPECT_GE(r.counts[4].mean, r.counts[5].mean);
    EXPECT_LE(r.counts[0].ci_low, r.counts[0].mean);
    EXPECT_GE(r.counts[0].ci_high, r.counts[0].mean);
  }
}

TEST(ParkwayStatistics, ConfidenceIntervalShrinksWithTrials) {
  mm::StatisticsOptions o;
  o.size = 100;
  o.windows = {5};
  o.populations = {200};
  o.trials = 8;
  const mm::Summary few = mm::parkway_statistics(o)[0].counts[0];
  o.trials = 64;
  const mm::Summary many = mm::parkway_statistics(o)[0].counts[0];
  // Width ~ t sd / sqrt(K): 8x the trials, about a third of the width (t also falls, 2.36 -> 2.00).
  EXPECT_LT(many.ci_high - many.ci_low, 0.7 * (few.ci_high - few.ci_low));
  EXPECT_GT(many.ci_high - many.ci_low, 0);
}

TEST(ParkwayStatistics, PoissonEstimateMatchesSimulationAtLowDensity) {
  const neopipe::nav::WindowModel window = neopipe::nav::WindowModel::with_side(3);
  EXPECT_DOUBLE_EQ(mm::poisson_new_parkway_probability(100, window, 0), 1);
  EXPECT_NEAR(mm::poisson_new_parkway_probability(100, window, 100), std::exp(-4 * 2.7 * 2.7 / 1e4 * 100), 1e-12);
  mm::StatisticsOptions o;
  o.size = 100;
  o.windows = {3};
  o.populations = {100};
  o.trials = 60;
  const auto row = mm::parkway_statistics(o)[0];
  const double simulated = row.counts[9].mean;  // new_parkways
  EXPECT_EQ(mm::count_names()[9], "new_parkways");
  // The world's edges shrink the neighbourhood of objects near them, so slightly more objects found
  // parkways than the unbounded Poisson model says; within 3% at this density (~0.07 per window).
  EXPECT_NEAR(simulated, row.poisson_new_parkways, 0.03 * row.poisson_new_parkways);
  EXPECT_GT(row.poisson_new_parkways, 80);
}

TEST(ParkwayStatistics, EdgeClippedPoissonExplainsTheExcessAtLargeWindows) {
  // A 10 x 10 window in a 100 x 100 world: objects near the edges have up to half their
  // neighbourhood outside, which the paper's formula ignores.
  const neopipe::nav::WindowModel window = neopipe::nav::WindowModel::with_side(10);
  EXPECT_GT(mm::poisson_expected_new_parkways_bounded(100, window, 200),
            mm::poisson_expected_new_parkways(100, window, 200));
  // Far from the edges (a huge world) the two agree.
  EXPECT_NEAR(mm::poisson_expected_new_parkways_bounded(1e5, window, 200),
              mm::poisson_expected_new_parkways(1e5, window, 200), 1e-3);
  EXPECT_DOUBLE_EQ(mm::poisson_expected_new_parkways_bounded(100, window, 0), 0);
  mm::StatisticsOptions o;
  o.size = 100;
  o.windows = {10};
  o.populations = {200};
  o.trials = 100;
  const auto row = mm::parkway_statistics(o)[0];
  EXPECT_NEAR(row.counts[9].mean, row.poisson_new_parkways_bounded, 0.03 * row.poisson_new_parkways_bounded);
  EXPECT_GT(row.counts[9].mean, 1.05 * row.poisson_new_parkways);
}

TEST(ParkwayStatistics, RejectsBadOptions) {
  mm::StatisticsOptions o = small_run();
  o.trials = 0;
  EXPECT_THROW(mm::parkway_statistics(o), mm::MapError);
  o = small_run();
  o.windows = {60};
  EXPECT_THROW(mm::parkway_statistics(o), mm::MapError);
}

}  // namespace
