// Rolling marbles: after many steps the marbles stay on the workspace, never sink into one another
// beyond a sliver, keep their kinetic energy (elastic bounces), and the same seed rolls the same way.

#include <gtest/gtest.h>

#include "sim/rolling_marbles.hpp"

namespace sim = neopipe::sim;

namespace {
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
  for (int i = 0; i < 300; ++i) m.step(1.0 / 30);
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
