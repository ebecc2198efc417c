// The unary operators L, R, I (spec qrm.md §3): Table I exactly, its properties, and random triangles
// through the classifier.

#include <gtest/gtest.h>

#include <array>
#include <random>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/operators.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

struct Row {
  StateSet l, r;
  State i;
};

// Table I, as printed.
const std::array<Row, 21> kTableI{{{},
                                   {{17}, {7}, 20},
                                   {{18}, {8}, 19},
                                   {{19}, {13}, 18},
                                   {{20}, {14}, 17},
                                   {{12}, {7}, 16},
                                   {{11}, {13}, 15},
                                   {{1, 5}, {12, 17}, 14},
                                   {{2, 10}, {15, 18}, 13},
                                   {{16}, {14}, 12},
                                   {{15}, {8}, 11},
                                   {{13}, {6}, 10},
                                   {{7}, {5}, 9},
                                   {{3, 6}, {11, 19}, 8},
                                   {{4, 9}, {16, 20}, 7},
                                   {{8}, {10}, 6},
                                   {{14}, {9}, 5},
                                   {{7}, {1}, 4},
                                   {{8}, {2}, 3},
                                   {{13}, {3}, 2},
                                   {{14}, {4}, 1}}};

}  // namespace

TEST(QrmOperators, TableIExactly) {
  for (State s = 1; s <= kStateCount; ++s) {
    EXPECT_EQ(left_shift(s), kTableI[s].l) << "L(" << s << ")";
    EXPECT_EQ(right_shift(s), kTableI[s].r) << "R(" << s << ")";
    EXPECT_EQ(inverse(s), kTableI[s].i) << "I(" << s << ")";
    EXPECT_EQ(inverse(StateSet{s}), StateSet{kTableI[s].i});
  }
}

TEST(QrmOperators, PropertiesOfSection3) {
  for (State s = 1; s <= kStateCount; ++s) {
    EXPECT_EQ(inverse(s), 21 - s);
    EXPECT_EQ(right_shift(s), inverse(left_shift(inverse(StateSet{s})))) << "R = I L I at " << s;
    EXPECT_TRUE(right_shift(left_shift(s)).contains(s)) << s;
    EXPECT_TRUE(left_shift(right_shift(s)).contains(s)) << s;
    EXPECT_TRUE(right_shift(s).subset_of(left_shift(left_shift(s)))) << s;
  }
  EXPECT_EQ(left_shift(StateSet{6, 7}), (StateSet{1, 5, 11}));  // the paper's §III-C example
  EXPECT_EQ(left_shift(StateSet{}), StateSet{});
  EXPECT_EQ(inverse(StateSet::all()), StateSet::all());
  EXPECT_EQ(inverse(StateSet{1, 5, 11}), (StateSet{20, 16, 10}));
}

TEST(QrmOperators, RandomTrianglesReproduceEveryRow) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::array<StateSet, 21> seen_l{};
  std::array<StateSet, 21> seen_r{};
  std::array<StateSet, 21> seen_i{};
  int triangles = 0;
  for (int n = 0; n < 300000; ++n) {
    const Eigen::Vector2d a{u(rng), u(rng)};
    const Eigen::Vector2d b{u(rng), u(rng)};
    const Eigen::Vector2d c{u(rng), u(rng)};
    const State s = classify(a, b, c);
    const State l = classify(b, c, a);
    const State r = classify(c, a, b);
    const State i = classify(b, a, c);
    if (s == 0 || l == 0 || r == 0 || i == 0) continue;
    ++triangles;
    seen_l[s].insert(l);
    seen_r[s].insert(r);
    seen_i[s].insert(i);
    ASSERT_TRUE(left_shift(s).contains(l)) << s << " -> " << l;
    ASSERT_TRUE(right_shift(s).contains(r)) << s << " -> " << r;
    ASSERT_EQ(inverse(s), i);
  }
  EXPECT_GT(triangles, 299000);
  for (State s = 1; s <= kStateCount; ++s) {
    EXPECT_EQ(seen_l[s], left_shift(s)) << s;
    EXPECT_EQ(seen_r[s], right_shift(s)) << s;
    EXPECT_EQ(seen_i[s], StateSet{inverse(s)}) << s;
  }
}
