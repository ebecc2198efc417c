// Branch and bound (spec qrm.md §5): small systems with known answers, and each exact lower bound
// against a brute-force grid over random boxes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "nav/qrm/branch_and_bound.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

Affine x(int i) {
  return Affine::unknown(i);
}
Affine k(double b) {
  return Affine::constant(b);
}
Product linear(const Affine& f) {
  return {1, k(1), f};
}

Box cube(int n, double lo, double hi) {
  Box b;
  for (int i = 0; i < n; ++i) {
    b.lo[i] = lo;
    b.hi[i] = hi;
  }
  return b;
}

// The minimum of g over a grid of the box (a point set of the box, so never below the true minimum).
double grid_min(const Quadratic& g, const Box& box, int steps) {
  const int n = g.unknowns();
  double best = INFINITY;
  std::vector<int> at(n, 0);
  for (;;) {
    Point4 p{};
    for (int i = 0; i < n; ++i) p[i] = box.lo[i] + (box.hi[i] - box.lo[i]) * at[i] / steps;
    best = std::min(best, g(p));
    int i = 0;
    while (i < n && ++at[i] > steps) at[i++] = 0;
    if (i == n) return best;
  }
}

// Random integer coefficients in -3..3 for the terms `use` allows.
Quadratic random_quadratic(std::mt19937_64& rng, int n, bool squares, bool crosses, int only_square = -1) {
  std::uniform_int_distribution<int> c(-3, 3);
  std::vector<Product> p;
  for (int i = 0; i < n; ++i) {
    p.push_back(linear(x(i) * c(rng)));
    if (squares && (only_square < 0 || only_square == i)) p.push_back({static_cast<double>(c(rng)), x(i), x(i)});
    for (int j = i + 1; j < n && crosses; ++j) p.push_back({static_cast<double>(c(rng)), x(i), x(j)});
  }
  p.push_back(linear(k(c(rng))));
  return {n, p};
}

void expect_exact_bounds(BoundKind kind, bool squares, bool crosses, bool one_square) {
  std::mt19937_64 rng(static_cast<int>(kind) + 11);
  std::uniform_real_distribution<double> u(-2, 2);
  int tested = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 2 + trial % 3;  // 2, 3, 4 unknowns
    const Quadratic g = random_quadratic(rng, n, squares, crosses, one_square ? trial % n : -1);
    if (g.bound_kind() != kind) continue;
    ++tested;
    Box box;
    for (int i = 0; i < n; ++i) {
      const double a = u(rng);
      const double b = u(rng);
      box.lo[i] = std::min(a, b);
      box.hi[i] = std::max(a, b) + 0.01;
    }
    const double bound = g.lower_bound(box);
    const double grid = grid_min(g, box, n == 4 ? 24 : 60);
    EXPECT_LE(bound, grid + 1e-9) << "a lower bound above a value of g";
    // Exact: the grid gets within its own resolution of the bound.
    EXPECT_NEAR(bound, grid, 0.05 * (1 + std::abs(grid)));
  }
  EXPECT_GT(tested, 100);
}

}  // namespace

TEST(QrmBranchAndBound, ClassifiesBoundKinds) {
  EXPECT_EQ(Quadratic(2, {linear(x(0) + x(1))}).bound_kind(), BoundKind::corners);
  EXPECT_EQ(Quadratic(2, {{1, x(0), x(1)}}).bound_kind(), BoundKind::corners);
  EXPECT_EQ(Quadratic(2, {{1, x(0), x(0)}, {-1, x(1), x(1)}}).bound_kind(), BoundKind::separable);
  EXPECT_EQ(Quadratic(2, {{1, x(0), x(0)}, {1, x(0), x(1)}}).bound_kind(), BoundKind::one_square);
  EXPECT_EQ(Quadratic(2, {{1, x(0) - x(1), x(0) - x(1)}}).bound_kind(), BoundKind::interval);
  // (x0 - x1)^2 - x0^2 - x1^2 = -2 x0 x1: the squares cancel, so the exact bound applies.
  EXPECT_EQ(Quadratic(2, {{1, x(0) - x(1), x(0) - x(1)}, {-1, x(0), x(0)}, {-1, x(1), x(1)}}).bound_kind(),
            BoundKind::corners);
}

TEST(QrmBranchAndBound, CornerBoundIsTheMinimumOverTheBox) {
  expect_exact_bounds(BoundKind::corners, false, true, false);
}
TEST(QrmBranchAndBound, SeparableBoundIsTheMinimumOverTheBox) {
  expect_exact_bounds(BoundKind::separable, true, false, false);
}
TEST(QrmBranchAndBound, OneSquareBoundIsTheMinimumOverTheBox) {
  expect_exact_bounds(BoundKind::one_square, true, true, true);
}

TEST(QrmBranchAndBound, IntervalBoundIsALowerBoundAndExactForASquareOfADifference) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 200; ++trial) {
    const Quadratic g = random_quadratic(rng, 3, true, true);
    const Box box = cube(3, -1 + 0.5 * u(rng), 1 + 0.5 * u(rng));
    EXPECT_LE(g.lower_bound(box), grid_min(g, box, 40) + 1e-9);
  }
  // (x0 - x1 - 1)^2 over [0, 1]^2 has minimum 0 (at x0 = 1, x1 = 0): squaring the interval of the
  // difference finds it; multiplying two copies of the interval would give -4.
  const Quadratic sq(2, {{1, x(0) - x(1) - k(1), x(0) - x(1) - k(1)}});
  EXPECT_EQ(sq.bound_kind(), BoundKind::interval);
  EXPECT_EQ(sq.lower_bound(cube(2, 0, 1)), 0.0);
  EXPECT_EQ(sq.lower_bound(cube(2, 2, 3)), 0.0);
  EXPECT_EQ(sq.lower_bound(cube(2, 0.5, 0.75)), 0.0625 * 9);  // x0 - x1 - 1 in [-1.25, -0.75]
}

TEST(QrmBranchAndBound, FindsAWitnessOfAFeasibleSystem) {
  // The open disk x^2 + y^2 < 1 and x + y > 1.2: a thin cap.
  const std::vector<Quadratic> g{Quadratic(2, {{1, x(0), x(0)}, {1, x(1), x(1)}, linear(k(-1))}),
                                 Quadratic(2, {linear(k(1.2) - x(0) - x(1))})};
  const Feasibility f = find_feasible(g, cube(2, -2, 2), 30);
  ASSERT_TRUE(f.witness.has_value());
  for (const Quadratic& q : g) EXPECT_LT(q(*f.witness), 0);
  // Deterministic: the same witness every time, after the same boxes.
  const Feasibility again = find_feasible(g, cube(2, -2, 2), 30);
  EXPECT_EQ(again.witness, f.witness);
  EXPECT_EQ(again.boxes, f.boxes);
  // Four unknowns: x0 x1 > 1, x2 x3 > 1, x0 + x2 < 2.5, all positive.
  const std::vector<Quadratic> h{Quadratic(4, {{-1, x(0), x(1)}, linear(k(1))}),
                                 Quadratic(4, {{-1, x(2), x(3)}, linear(k(1))}),
                                 Quadratic(4, {linear(x(0) + x(2) - k(2.5))})};
  const Feasibility f4 = find_feasible(h, cube(4, 0, 4), 40);
  ASSERT_TRUE(f4.witness.has_value());
  for (const Quadratic& q : h) EXPECT_LT(q(*f4.witness), 0);
}

TEST(QrmBranchAndBound, ProvesInfeasibleSystemsInfeasible) {
  // x^2 + y^2 < 1 and x + y > 1.5: the line misses the disk.
  const std::vector<Quadratic> g{Quadratic(2, {{1, x(0), x(0)}, {1, x(1), x(1)}, linear(k(-1))}),
                                 Quadratic(2, {linear(k(1.5) - x(0) - x(1))})};
  const Feasibility f = find_feasible(g, cube(2, -2, 2), 30);
  EXPECT_FALSE(f.witness.has_value());
  EXPECT_GT(f.boxes, 1);
  // x < 0 and x > 0 (touching closures): no witness at any depth.
  const std::vector<Quadratic> h{Quadratic(2, {linear(x(0))}), Quadratic(2, {linear(x(0) * -1)})};
  EXPECT_FALSE(find_feasible(h, cube(2, -1, 1), 16).witness.has_value());
  // (x0 - x1)^2 < 0 over four unknowns' box, through the interval bound.
  const std::vector<Quadratic> s{Quadratic(4, {{1, x(0) - x(1), x(0) - x(1)}, {1, x(2), x(3)}, {-1, x(2), x(3)}})};
  EXPECT_FALSE(find_feasible(s, cube(4, -1, 1), 12).witness.has_value());
}

TEST(QrmBranchAndBound, SplitsTheLongestEdgeLowerHalfFirst) {
  // Feasible in two places, x0 < -0.5 and x0 > 0.5 (with x1 free): the lower half comes first, so the
  // witness has x0 < 0.
  const std::vector<Quadratic> g{Quadratic(2, {{-1, x(0), x(0)}, linear(k(0.25))})};
  const Feasibility f = find_feasible(g, cube(2, -1, 1), 10);
  ASSERT_TRUE(f.witness.has_value());
  EXPECT_LT((*f.witness)[0], 0);
  // The root's centre already works: one box.
  const std::vector<Quadratic> h{Quadratic(2, {linear(x(0) - k(1))})};
  EXPECT_EQ(find_feasible(h, cube(2, -1, 1), 10).boxes, 1);
}
