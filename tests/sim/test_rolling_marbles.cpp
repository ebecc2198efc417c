// Rolling marbles: after many steps the marbles stay on the workspace, never sink into one another
// beyond a sliver, keep their total kinetic energy (bounces off the edges and off one another are
// elastic, between equal masses) while collisions share it out unevenly, and the same seed rolls the
// same way.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "sim/rolling_marbles.hpp"

namespace sim = neopipe::sim;

namespace {
// Kinetic energy per unit mass, summed over the marbles (every marble has the same mass), mm^2/s^2.
double kinetic_energy(const sim::RollingMarbles& m) {
  double e = 0;
  for (const auto& v : m.velocities()) e += 0.5 * v.squaredNorm();
  return e;
}

sim::World crowded() {
  sim::WorldRequest q;
  q.objects = 400;
  q.size = {200, 200};
  q.min_gap = 1;
  q.seed = 5;
  return sim::generate_world(q);
}
}  // namespace

TEST(RollingMarbles, StayApartOnTheWorkspaceAndKeepTheirEnergy) {
  const sim::World w = crowded();
  sim::RollingMarbles m(w, 40, 3);
  const double n = static_cast<double>(w.objects.size());
  const double start_energy = kinetic_energy(m);
  ASSERT_NEAR(start_energy, n * 0.5 * 40 * 40, 1e-9 * start_energy);  // every marble starts at 40 mm/s
  double worst_drift = 0;  // largest relative change of the total, after any frame
  for (int i = 0; i < 300; ++i) {
    m.step(1.0 / 30);
    worst_drift = std::max(worst_drift, std::abs(kinetic_energy(m) - start_energy) / start_energy);
  }
  // Elastic bounces and equal-mass exchanges along the line of centres keep the total exactly, so
  // only rounding remains (measured: 1.8e-15); a lossy bounce anywhere in 10 s would show far above this.
  EXPECT_LT(worst_drift, 1e-12);
  // ... while the collisions share it out: speeds no longer all 40 mm/s, or energy kept would be
  // nothing more than marbles that never met.
  int changed = 0;
  double fastest = 0;
  for (const auto& v : m.velocities()) {
    if (std::abs(v.norm() - 40) > 1) ++changed;
    fastest = std::max(fastest, v.norm());
  }
  EXPECT_GT(changed, static_cast<int>(w.objects.size()) / 2);
  EXPECT_GT(fastest, 40 * 1.2);
  std::printf("[ measured ] 400 marbles, 10 s: kinetic energy drift %.3g (relative), %d of 400 speeds changed\n",
              worst_drift, changed);
  const auto& p = m.positions();
  ASSERT_EQ(p.size(), w.objects.size());
  double closest = 1e9;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GE(p[i].x(), 2.5 - 0.05);
    EXPECT_LE(p[i].x(), 197.5 + 0.05);
    EXPECT_GE(p[i].y(), 2.5 - 0.05);
    EXPECT_LE(p[i].y(), 197.5 + 0.05);
    for (std::size_t j = 0; j < i; ++j) closest = std::min(closest, (p[i] - p[j]).norm());
  }
  EXPECT_GT(closest, 5.0 - 0.25);
  // Did they move at all (and far)? The mean displacement of a marble rolling 10 s at 40 mm/s in a
  // crowd is tens of mm.
  double moved = 0;
  for (std::size_t i = 0; i < p.size(); ++i) moved += (p[i] - w.objects[i]).norm();
  EXPECT_GT(moved / static_cast<double>(p.size()), 20.0);
}

TEST(RollingMarbles, SameSeedSameRoll) {
  const sim::World w = crowded();
  sim::RollingMarbles a(w, 30, 8);
  sim::RollingMarbles b(w, 30, 8);
  sim::RollingMarbles c(w, 30, 9);
  for (int i = 0; i < 50; ++i) {
    a.step(0.05);
    b.step(0.05);
    c.step(0.05);
  }
  for (std::size_t i = 0; i < w.objects.size(); ++i) EXPECT_EQ(a.positions()[i], b.positions()[i]);
  EXPECT_NE(a.positions()[0], c.positions()[0]);
}

TEST(RollingMarbles, ZeroSpeedStandsStill) {
  const sim::World w = crowded();
  sim::RollingMarbles m(w, 0, 1);
  m.step(10);
  for (std::size_t i = 0; i < w.objects.size(); ++i) EXPECT_EQ(m.positions()[i], w.objects[i]);
}
