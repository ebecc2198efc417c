// Measurements from bearings and a range order (spec qrm.md §6).

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/measurement.hpp"
#include "scenes.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)
}  // namespace

TEST(QrmMeasurement, WorkedExampleForEveryRho) {
  // O (0,0), A (4,0), B (0,3), C (3,3): bearings 0, 90, 45 degrees, order B < A < C.
  const RangeOrder order{-1, +1, +1};
  for (const double rho : {10.0, 100.0, 1000.0}) {
    MeasurementOptions options;
    options.rho = rho;
    EXPECT_EQ(feasible_states(0, M_PI / 2, M_PI / 4, order, StateSet::all(), options), (StateSet{8, 14, 15, 16, 20}))
        << "rho " << rho;
  }
  EXPECT_EQ(classify({4, 0}, {0, 3}, {3, 3}), 8);
  // Any zero direction: the same bearings turned.
  EXPECT_EQ(feasible_states(2.0, 2.0 + M_PI / 2, 2.0 + M_PI / 4, order, StateSet::all()),
            (StateSet{8, 14, 15, 16, 20}));
  // Only the candidates are tested.
  EXPECT_EQ(feasible_states(0, M_PI / 2, M_PI / 4, order, StateSet{1, 8, 9, 20}), (StateSet{8, 20}));
}

TEST(QrmMeasurement, RangeOrderOmitsEstimatesWithinTau) {
  const RangeOrder o = range_order(4, 3, 3 * std::sqrt(2.0), 0.1);
  EXPECT_EQ(o.b_vs_a, -1);  // 3 < 4 / 1.1
  EXPECT_EQ(o.c_vs_a, 0);   // 4.24 is within a factor 1.1 of 4
  EXPECT_EQ(o.c_vs_b, 1);
  const RangeOrder tight = range_order(4, 3, 3 * std::sqrt(2.0), 0.01);
  EXPECT_EQ(tight.c_vs_a, 1);
  // The example's scene from its sightings: with A and C unordered the set can only grow.
  const StateSet m =
      measure({Sighting{0, 4}, Sighting{M_PI / 2, 3}, Sighting{M_PI / 4, 3 * std::sqrt(2.0)}}, StateSet::all());
  EXPECT_TRUE((StateSet{8, 14, 15, 16, 20}).subset_of(m));
  EXPECT_TRUE(m.contains(8));
}

TEST(QrmMeasurement, TheTrueStateIsAlwaysMeasured) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(0, 100);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  int scenes = 0;
  int total_states = 0;
  while (scenes < 400) {
    const Eigen::Vector2d a{u(rng), u(rng)};
    const Eigen::Vector2d b{u(rng), u(rng)};
    const Eigen::Vector2d c{u(rng), u(rng)};
    const Eigen::Vector2d camera{u(rng), u(rng)};
    const State truth = classify(a, b, c);
    if (truth == 0 || (a - camera).norm() < 1 || (b - camera).norm() < 1 || (c - camera).norm() < 1) continue;
    ++scenes;
    const StateSet m = measure(scenes::sightings(camera, turn(rng), a, b, c), StateSet::all());
    EXPECT_TRUE(m.contains(truth)) << "truth " << truth << " measured " << m;
    total_states += m.count();
  }
  // Bearings and an order say something: on average well under the 20 states.
  EXPECT_LT(total_states, 400 * 12);
}
