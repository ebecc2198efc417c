// The measurement's speed-ups change no result (issue 20): the two-unknown bounds equal the generic
// ones (bit for bit, but for the rounding of fused multiply-adds in the one-square bound),
// feasible_states equals spec §5's search as first written (each state's constraints built afresh,
// both halves of a split pushed, the generic bounds) on random scenes, near-degenerate ones
// included, and 3000 fixed scenes give the feasible sets the implementation before the speed-ups
// gave (their digest, recorded from it).

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "nav/qrm/branch_and_bound.hpp"
#include "nav/qrm/measurement.hpp"
#include "nav/qrm/region_constraints.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

// Spec §5's depth-first search as it was first written, with the generic bounds.
bool reference_feasible(const std::vector<Quadratic>& g, const Box& box, int max_depth) {
  struct Pending {
    Box box;
    int depth;
  };
  const int n = g.front().unknowns();
  std::vector<Pending> stack{{box, 0}};
  while (!stack.empty()) {
    const Pending at = stack.back();
    stack.pop_back();
    const bool discarded =
        std::any_of(g.begin(), g.end(), [&](const Quadratic& q) { return q.lower_bound_generic(at.box) >= 0; });
    if (discarded) continue;
    Point4 centre{};
    for (int i = 0; i < n; ++i) centre[i] = 0.5 * (at.box.lo[i] + at.box.hi[i]);
    // The generic evaluation, term by term as Quadratic's general case does it.
    const auto value = [&](const Quadratic& q) {
      double v = q.constant();
      for (int i = 0; i < n; ++i) {
        double row = q.square(i) * centre[i] + q.linear(i);
        for (int j = i + 1; j < n; ++j) row += q.cross(i, j) * centre[j];
        v += row * centre[i];
      }
      return v;
    };
    if (std::all_of(g.begin(), g.end(), [&](const Quadratic& q) { return value(q) < 0; })) return true;
    if (at.depth >= max_depth) continue;
    int axis = 0;
    for (int i = 1; i < n; ++i) {
      if (at.box.hi[i] - at.box.lo[i] > at.box.hi[axis] - at.box.lo[axis]) axis = i;
    }
    Pending lower{at.box, at.depth + 1};
    Pending upper{at.box, at.depth + 1};
    lower.box.hi[axis] = centre[axis];
    upper.box.lo[axis] = centre[axis];
    stack.push_back(upper);
    stack.push_back(lower);
  }
  return false;
}

// The measurement as first written: order constraints, then each state's region constraints.
StateSet reference_states(double bearing_a, double bearing_b, double bearing_c, const RangeOrder& order,
                          StateSet candidates) {
  const double beta = bearing_b - bearing_a;
  const double gamma = bearing_c - bearing_a;
  const AffinePoint a{Affine::constant(1), Affine::constant(0)};
  const AffinePoint b{Affine::unknown(0) * std::cos(beta), Affine::unknown(0) * std::sin(beta)};
  const AffinePoint c{Affine::unknown(1) * std::cos(gamma), Affine::unknown(1) * std::sin(gamma)};
  std::vector<Quadratic> common;
  const auto add = [&](int sign, const Affine& later, const Affine& earlier) {
    if (sign != 0) common.emplace_back(2, std::vector<Product>{{double(sign), Affine::constant(1), earlier - later}});
  };
  add(order.b_vs_a, Affine::unknown(0), Affine::constant(1));
  add(order.c_vs_a, Affine::unknown(1), Affine::constant(1));
  add(order.c_vs_b, Affine::unknown(1), Affine::unknown(0));
  Box box;
  box.lo = {0.01, 0.01, 0, 0};
  box.hi = {100, 100, 0, 0};
  StateSet feasible;
  for (const State s : candidates) {
    std::vector<Quadratic> g = common;
    for (Quadratic& q : region_constraints(2, a, b, c, s)) g.push_back(std::move(q));
    if (reference_feasible(g, box, 30)) feasible.insert(s);
  }
  return feasible;
}

// Scenes from a fixed generator (SplitMix64: the same numbers on every standard library).
struct SplitMix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31U);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11U) * 0x1.0p-53; }
};

// FNV-1a over the feasible sets of `scenes` measurements: every third with B at nearly A's bearing
// (the near-degenerate problems), every fourth on a random subset of candidates.
std::uint64_t measurement_digest(int scenes) {
  SplitMix random{2026};
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (int scene = 0; scene < scenes; ++scene) {
    const double cx = random.uniform(0, 500);
    const double cy = random.uniform(0, 500);
    std::array<Sighting, 3> s{};
    for (Sighting& x : s) {
      const double dx = random.uniform(0, 500) - cx;
      const double dy = random.uniform(0, 500) - cy;
      x = {std::atan2(dy, dx) + 0.7 * scene, std::hypot(dx, dy)};
    }
    if (scene % 3 == 2) s[1].bearing = s[0].bearing + random.uniform(-0.03, 0.03);
    StateSet candidates = StateSet::all();
    if (scene % 4 == 1) candidates = StateSet::from_mask(static_cast<StateSet::Mask>(random.next()));
    const StateSet::Mask m = measure(s, candidates).mask();
    for (int byte = 0; byte < 4; ++byte) {
      hash ^= (m >> (8 * byte)) & 0xFFU;
      hash *= 0x100000001b3ULL;
    }
  }
  return hash;
}

TEST(QrmFastPaths, FixedScenesGiveTheSetsOfTheImplementationBeforeTheSpeedUps) {
  // Recorded with the library of commit fc50591 (before the speed-ups). A change here means some
  // measurement's result changed: find out why before updating it.
  EXPECT_EQ(measurement_digest(3000), 0xb9222af6aed0e9fcULL);
}

TEST(QrmFastPaths, TwoUnknownBoundsEqualTheGenericOnes) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3, 3);
  std::uniform_real_distribution<double> pos(0.01, 100);
  int kinds[4] = {};
  int differ[4] = {};
  for (int trial = 0; trial < 20000; ++trial) {
    // Bearings of a measurement problem, so every kind of constraint it builds turns up.
    const double beta = u(rng);
    const double gamma = u(rng);
    const AffinePoint a{Affine::constant(1), Affine::constant(0)};
    const AffinePoint b{Affine::unknown(0) * std::cos(beta), Affine::unknown(0) * std::sin(beta)};
    const AffinePoint c{Affine::unknown(1) * std::cos(gamma), Affine::unknown(1) * std::sin(gamma)};
    std::vector<Quadratic> g;
    for (const Quadratic& q : edc_quadratics(2, a, b, c)) {
      g.push_back(q);
      g.push_back(q.negated());
    }
    g.emplace_back(2, std::vector<Product>{{1, Affine::constant(1), Affine::unknown(0) - Affine::constant(1)}});
    g.emplace_back(2, std::vector<Product>{{-1, Affine::constant(1), Affine::unknown(1) - Affine::unknown(0)}});
    g.emplace_back(
        2, std::vector<Product>{{u(rng), Affine::unknown(1), Affine::unknown(1)},
                                {u(rng), Affine::unknown(0) + Affine::constant(u(rng)), Affine::unknown(0) * u(rng)}});
    double x0 = pos(rng);
    double x1 = pos(rng);
    double y0 = pos(rng);
    double y1 = pos(rng);
    Box box;
    box.lo = {std::min(x0, y0), std::min(x1, y1), 0, 0};
    box.hi = {std::max(x0, y0), std::max(x1, y1), 0, 0};
    for (const Quadratic& q : g) {
      ++kinds[static_cast<int>(q.bound_kind())];
      const double fast = q.lower_bound(box);
      const double generic = q.lower_bound_generic(box);
      if (q.bound_kind() == BoundKind::one_square) {
        // The specialised path evaluates in scalars, which the compiler may fuse differently: equal
        // up to the rounding of terms as large as the box's squared corner.
        const double terms = 1 + box.hi[0] * box.hi[0] + box.hi[1] * box.hi[1];
        EXPECT_NEAR(fast, generic, 1e-13 * terms);
      } else if (std::bit_cast<std::uint64_t>(fast) != std::bit_cast<std::uint64_t>(generic)) {
        ++differ[static_cast<int>(q.bound_kind())];
      }
    }
  }
  EXPECT_EQ(differ[0], 0);
  EXPECT_EQ(differ[1], 0);
  EXPECT_EQ(differ[3], 0);
  EXPECT_GT(kinds[static_cast<int>(BoundKind::corners)], 0);
  EXPECT_GT(kinds[static_cast<int>(BoundKind::separable)], 0);
  EXPECT_GT(kinds[static_cast<int>(BoundKind::one_square)], 0);
}

TEST(QrmFastPaths, MeasurementsEqualTheSearchAsFirstWritten) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0, 500);
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> near(0, 0.02);
  int nonempty = 0;
  for (int scene = 0; scene < 600; ++scene) {
    const double cx = u(rng);
    const double cy = u(rng);
    std::array<double, 3> bearing{};
    std::array<double, 3> range{};
    for (int i = 0; i < 3; ++i) {
      const double dx = u(rng) - cx;
      const double dy = u(rng) - cy;
      bearing[i] = std::atan2(dy, dx) + 0.7 * scene;
      range[i] = std::hypot(dx, dy);
    }
    // A third of the scenes put B at nearly A's bearing: the slowest, near-degenerate problems.
    if (scene % 3 == 2) bearing[1] = bearing[0] + near(rng);
    const RangeOrder order = range_order(range[0], range[1], range[2], 0.1);
    StateSet candidates = StateSet::all();
    if (scene % 4 == 1) {
      candidates = {};
      for (State s = 1; s <= kStateCount; ++s) {
        if (unit(rng) < 0.4) candidates.insert(s);
      }
    }
    const StateSet fast = feasible_states(bearing[0], bearing[1], bearing[2], order, candidates);
    ASSERT_EQ(fast, reference_states(bearing[0], bearing[1], bearing[2], order, candidates)) << "scene " << scene;
    nonempty += fast.empty() ? 0 : 1;
  }
  EXPECT_GT(nonempty, 400);
}

}  // namespace
