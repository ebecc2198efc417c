// QRM map building runs (rig/qrm_build.hpp): one build with its metrics after every image, and the
// Monte Carlo's rows in a fixed order with the same numbers whatever the threads did.

#include <gtest/gtest.h>

#include <stdexcept>

#include "rig/qrm_build.hpp"

namespace neopipe::rig {
namespace {

TEST(QrmBuild, MetricsAfterEveryImage) {
  sim::WorldRequest request;
  request.objects = 12;
  request.seed = 2;
  const sim::World world = generate_qrm_world(request);
  QrmBuildSettings settings;
  settings.images = 6;
  settings.nearest = 8;
  std::size_t calls = 0;
  const QrmBuildResult r = build_qrm_map(world, settings, [&](std::size_t done) { EXPECT_EQ(done, ++calls); });
  ASSERT_EQ(r.steps.size(), 6U);
  EXPECT_EQ(calls, 6U);
  EXPECT_EQ(r.positions.size(), 6U);
  double m1 = 0;
  for (const QrmBuildStep& s : r.steps) {
    EXPECT_EQ(s.image.fused.triples, 56U);  // C(8, 3)
    EXPECT_GE(s.metrics.m1, m1);            // removed states stay removed
    m1 = s.metrics.m1;
    EXPECT_GT(s.m5_us, 0);
    EXPECT_EQ(s.metrics.lost, 0U);
  }
  EXPECT_GT(m1, 20);
  EXPECT_EQ(r.true_rng, QrmTruth(world.objects).rng());
}

TEST(QrmBuild, RejectsWhatCannotBeMapped) {
  sim::World two;
  two.objects = {{100, 100}, {200, 200}};
  EXPECT_THROW(build_qrm_map(two, {}), std::invalid_argument);
  sim::WorldRequest request;
  request.objects = 5;
  const sim::World world = generate_qrm_world(request);
  QrmBuildSettings settings;
  settings.nearest = 2;
  EXPECT_THROW(build_qrm_map(world, settings), std::invalid_argument);
}

TEST(QrmBuild, ExperimentRowsAreOrderedAndRepeat) {
  QrmExperimentSettings settings;
  settings.runs = 4;
  settings.marbles = 10;
  settings.nearest = {4, 8};
  settings.build.images = 3;
  const auto a = run_qrm_experiment(settings);
  const auto b = run_qrm_experiment(settings);
  ASSERT_EQ(a.size(), 4U * 2U * 3U);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].run, i / 6);
    EXPECT_EQ(a[i].nearest, (i / 3) % 2 == 0 ? 4U : 8U);
    EXPECT_EQ(a[i].image, i % 3 + 1);
    EXPECT_EQ(a[i].m1, b[i].m1);
    EXPECT_EQ(a[i].m2, b[i].m2);
    EXPECT_EQ(a[i].m3, b[i].m3);
    EXPECT_EQ(a[i].m4, b[i].m4);
    EXPECT_EQ(a[i].rng_precision, b[i].rng_precision);
    EXPECT_EQ(a[i].triples, a[i].nearest == 4 ? 4U : 56U);
  }
  // Different runs are different worlds.
  EXPECT_NE(a[2].m1, a[8].m1);
}

}  // namespace
}  // namespace neopipe::rig
