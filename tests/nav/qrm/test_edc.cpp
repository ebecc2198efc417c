// The EDC regions (spec qrm.md §2): the numbering through its sample points, its symmetries, the
// degenerate rule, the adjacency list, and sets of states.

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "nav/qrm/edc.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

const Eigen::Vector2d kA{0, 0};
const Eigen::Vector2d kB{0, 1};

}  // namespace

TEST(QrmEdc, EverySamplePointOfTheSpecTableHasItsState) {
  // The table of spec §2, literally: (left, right, sample C on the left).
  const struct {
    State left, right;
    double x, y;
  } rows[] = {{1, 2, -2, 3},     {3, 4, -0.5, 1.5},   {5, 10, -2, 0.8},    {6, 9, -0.9, 0.9},    {7, 8, -0.3, 0.7},
              {11, 16, -2, 0.2}, {12, 15, -0.9, 0.1}, {13, 14, -0.3, 0.3}, {17, 18, -0.5, -0.5}, {19, 20, -2, -2}};
  for (const auto& r : rows) {
    EXPECT_EQ(classify(kA, kB, {r.x, r.y}), r.left) << r.x << "," << r.y;
    EXPECT_EQ(classify(kA, kB, {-r.x, r.y}), r.right) << -r.x << "," << r.y;
    EXPECT_EQ(sample_point(r.left), Eigen::Vector2d(r.x, r.y));
    EXPECT_EQ(sample_point(r.right), Eigen::Vector2d(-r.x, r.y));
  }
}

TEST(QrmEdc, SignTableAgreesWithTheClassifierAtEverySample) {
  for (State s = 1; s <= kStateCount; ++s) {
    const auto e = edc_values(kA, kB, sample_point(s));
    for (int i = 0; i < 6; ++i) EXPECT_EQ(e[i] > 0 ? 1 : -1, state_signs(s)[i]) << "state " << s << " e" << i + 1;
  }
}

TEST(QrmEdc, ReflectionsSwapWithinARowAndMapSTo21MinusS) {
  std::mt19937_64 rng(20);
  std::uniform_real_distribution<double> u(-10, 10);
  int checked = 0;
  for (int n = 0; n < 100000; ++n) {
    const Eigen::Vector2d a{u(rng), u(rng)};
    const Eigen::Vector2d b{u(rng), u(rng)};
    const Eigen::Vector2d c{u(rng), u(rng)};
    const State s = classify(a, b, c);
    if (s == 0) continue;
    ++checked;
    // Across line AB: reflect C.
    const Eigen::Vector2d d = (b - a).normalized();
    const Eigen::Vector2d foot = a + d * d.dot(c - a);
    EXPECT_EQ(classify(a, b, 2 * foot - c), mirror(s));
    // Through the midpoint of AB: C -> A + B - C.
    EXPECT_EQ(classify(a, b, a + b - c), kStateCount + 1 - s);
    // The state does not depend on where, how large or how turned the triangle is.
    const Eigen::Vector2d shift{u(rng), u(rng)};
    EXPECT_EQ(classify(3 * a + shift, 3 * b + shift, 3 * c + shift), s);
    EXPECT_EQ(classify(Eigen::Vector2d(-a.y(), a.x()), Eigen::Vector2d(-b.y(), b.x()), Eigen::Vector2d(-c.y(), c.x())),
              s);
  }
  EXPECT_GT(checked, 99000);
  for (State s = 1; s <= kStateCount; ++s) EXPECT_EQ(mirror(mirror(s)), s);
}

TEST(QrmEdc, BoundariesAndCoincidentPointsAreDegenerate) {
  EXPECT_EQ(classify(kA, kB, {0, 2}), 0);       // on line AB
  EXPECT_EQ(classify(kA, kB, {-0.3, 0.5}), 0);  // on the perpendicular bisector
  EXPECT_EQ(classify(kA, kB, {-1, 0}), 0);      // on the circle around A through B (and behind-A line)
  EXPECT_EQ(classify(kA, kB, {-0.6, 1.8}), 0);  // on the circle around B through A
  EXPECT_EQ(classify(kA, kA, {1, 1}), 0);       // A = B
  EXPECT_EQ(classify(kA, kB, kA), 0);           // C = A
  EXPECT_EQ(classify(kA, kB, {-2e-10, 3}), 0);  // within 1e-9 |AB|^2 of the line
  EXPECT_EQ(classify(kA, kB, {-2e-9, 3}), 1);   // just outside the tolerance
  // The tolerance scales with |AB|^2: the same shape a thousand times larger is as degenerate.
  EXPECT_EQ(classify(kA * 1e3, kB * 1e3, Eigen::Vector2d(-2e-10, 3) * 1e3), 0);
}

TEST(QrmEdc, AdjacencyHas70SymmetricPairsAndMatchesNeighbouringSamples) {
  int pairs = 0;
  for (State s = 1; s <= kStateCount; ++s) {
    EXPECT_FALSE(adjacent(s).contains(s));
    for (const State t : adjacent(s)) {
      EXPECT_TRUE(adjacent(t).contains(s)) << s << " - " << t;
      if (s < t) ++pairs;
      // The symmetries of the plane keep adjacency.
      EXPECT_TRUE(adjacent(mirror(s)).contains(mirror(t)));
      EXPECT_TRUE(adjacent(kStateCount + 1 - s).contains(kStateCount + 1 - t));
    }
  }
  EXPECT_EQ(pairs, 70);
  // Points close together on either side of a boundary are in adjacent regions.
  std::mt19937_64 rng(70);
  std::uniform_real_distribution<double> u(-3, 3);
  std::uniform_real_distribution<double> small(-1e-3, 1e-3);
  for (int n = 0; n < 200000; ++n) {
    const Eigen::Vector2d c{u(rng), u(rng)};
    const State s = classify(kA, kB, c);
    const State t = classify(kA, kB, c + Eigen::Vector2d(small(rng), small(rng)));
    if (s != 0 && t != 0 && s != t) {
      EXPECT_TRUE(adjacent(s).contains(t)) << s << " " << t;
    }
  }
}

TEST(QrmStateSet, IteratesCountsAndPrints) {
  const StateSet s{11, 1, 5};
  EXPECT_EQ(s.count(), 3);
  EXPECT_EQ(s.to_string(), "{1,5,11}");
  std::ostringstream out;
  out << s << StateSet{};
  EXPECT_EQ(out.str(), "{1,5,11}{}");
  std::vector<State> seen(s.begin(), s.end());
  EXPECT_EQ(seen, (std::vector<State>{1, 5, 11}));
  EXPECT_TRUE(StateSet::all().is_all());
  EXPECT_EQ(StateSet::all().count(), 20);
  EXPECT_EQ(StateSet::range(5, 20).count(), 16);
  EXPECT_EQ((StateSet{1, 2} & StateSet{2, 3}), StateSet{2});
  EXPECT_EQ(StateSet{7}.single(), 7);
  EXPECT_EQ(StateSet({7, 8}).single(), 0);
  EXPECT_FALSE(StateSet{0}.contains(0));  // state 0 is not a state
  EXPECT_TRUE(StateSet::from_mask(1U).empty());
  EXPECT_EQ(kLune, (StateSet{7, 8, 13, 14}));
}
