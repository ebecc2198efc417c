// LPB orientation and parts (spec qualnav.md §4, §10): the worked example, bearings against world
// positions on random observers, the sign vectors.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "nav/qualnav/topology/lpb.hpp"

namespace {
namespace qn = neopipe::nav::qualnav;
using Eigen::Vector2d;

double bearing_to(const Vector2d& from, const Vector2d& to) {
  return std::atan2(to.y() - from.y(), to.x() - from.x());
}

}  // namespace

TEST(QualnavLpb, WorkedExampleOfSection10) {
  const Vector2d l1(-1, 1);
  const Vector2d l2(1, 1);
  EXPECT_EQ(qn::orientation_from_positions(l1, l2, {0, 0}), +1);
  EXPECT_EQ(qn::orientation_from_positions(l1, l2, {0, 2}), -1);
  EXPECT_EQ(qn::orientation_from_positions(l1, l2, {0, 1}), 0);
  EXPECT_EQ(qn::part_of_line(l1, l2, {0, 1}), qn::LpbPart::b);
  // The same from the bearings a panorama at each observer would give.
  for (const auto& [o, expected] : std::vector<std::pair<Vector2d, int>>{{{0, 0}, +1}, {{0, 2}, -1}}) {
    EXPECT_EQ(qn::orientation_from_bearings(bearing_to(o, l1), bearing_to(o, l2)), expected) << o.transpose();
  }
  EXPECT_EQ(qn::orientation_from_bearings(bearing_to({0, 1}, l1), bearing_to({0, 1}, l2), 1e-12), 0);
}

TEST(QualnavLpb, PanAngleIsClockwiseFromL1ToL2) {
  constexpr double kPi = std::numbers::pi;
  EXPECT_NEAR(qn::pan_angle(kPi / 2, 0), kPi / 2, 1e-15);      // L1 north, L2 east: 90° clockwise
  EXPECT_NEAR(qn::pan_angle(0, kPi / 2), 3 * kPi / 2, 1e-15);  // the other way round
  EXPECT_NEAR(qn::pan_angle(-7 * kPi, kPi), 0, 1e-12);         // any range of bearings
  EXPECT_GE(qn::pan_angle(1e-18, 0), 0);
  EXPECT_LT(qn::pan_angle(0, 1e-18), 2 * kPi);
}

TEST(QualnavLpb, PartsOfTheLine) {
  const Vector2d l1(0, 0);
  const Vector2d l2(10, 0);
  EXPECT_EQ(qn::part_of_line(l1, l2, {-3, 0}), qn::LpbPart::l);
  EXPECT_EQ(qn::part_of_line(l1, l2, {4, 0}), qn::LpbPart::b);
  EXPECT_EQ(qn::part_of_line(l1, l2, {13, 0}), qn::LpbPart::r);
  EXPECT_EQ(qn::part_letter(qn::part_of_line(l2, l1, {13, 0})), 'l');
  EXPECT_THROW((void)qn::part_of_line(l1, l1, {1, 0}), std::invalid_argument);
}

// Bearings and positions are two ways to the same side: random landmarks and observers agree, and
// swapping the pair flips the sign.
TEST(QualnavLpb, BearingsAgreeWithPositionsOnRandomObservers) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0, 500);
  int agree = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vector2d l1(u(rng), u(rng));
    const Vector2d l2(u(rng), u(rng));
    const Vector2d o(u(rng), u(rng));
    const int by_position = qn::orientation_from_positions(l1, l2, o);
    const int by_bearing = qn::orientation_from_bearings(bearing_to(o, l1) + 4 * std::numbers::pi, bearing_to(o, l2));
    ASSERT_EQ(by_position, by_bearing) << l1.transpose() << " | " << l2.transpose() << " | " << o.transpose();
    ASSERT_EQ(qn::orientation_from_positions(l2, l1, o), -by_position);
    agree += by_position != 0;
  }
  EXPECT_EQ(agree, 20000);
}

TEST(QualnavLpb, SignVectorsOverPairs) {
  const std::vector<Vector2d> marbles{{0, 0}, {100, 0}, {0, 100}};
  const std::vector<qn::LandmarkId> ids{0, 1, 2};
  const auto pairs = qn::all_pairs(ids);
  ASSERT_EQ(pairs.size(), 3U);
  EXPECT_EQ(pairs[1], (qn::LandmarkPair{0, 2}));
  const Vector2d inside(20, 20);
  const qn::SignVector s = qn::sign_vector(marbles, pairs, inside);
  // From inside the triangle 0 -> 1 -> 2 (counter-clockwise), (0,1): 0 is seen clockwise-left of 1.
  EXPECT_EQ(s, (qn::SignVector{-1, +1, -1}));
  std::vector<qn::Sighting> seen;
  for (qn::LandmarkId i = 0; i < 3; ++i) seen.push_back({i, bearing_to(inside, marbles[i])});
  EXPECT_EQ(qn::sign_vector_from_bearings(seen, pairs), s);
  EXPECT_THROW((void)qn::sign_vector_from_bearings(std::span(seen).first(2), pairs), std::invalid_argument);
  const std::vector<qn::LandmarkPair> beyond{{0, 3}};
  EXPECT_THROW((void)qn::sign_vector(marbles, beyond, inside), std::out_of_range);
}

// §4's Decision: b when the pair was more than 90° apart before the flip, else beyond the nearer.
TEST(QualnavLpb, CrossingTypes) {
  constexpr double kDeg = std::numbers::pi / 180;
  EXPECT_EQ(qn::classify_crossing(100 * kDeg, -10 * kDeg, 50, 40), qn::LpbPart::b);  // 110° apart
  EXPECT_EQ(qn::classify_crossing(350 * kDeg, 250 * kDeg, 50, 40), qn::LpbPart::b);  // 100° the other way
  EXPECT_EQ(qn::classify_crossing(80 * kDeg, 0, 30, 40), qn::LpbPart::l);            // L1 nearer
  EXPECT_EQ(qn::classify_crossing(80 * kDeg, 0, 50, 40), qn::LpbPart::r);            // L2 nearer
  EXPECT_EQ(qn::classify_crossing(10 * kDeg, 300 * kDeg, 30, 40), qn::LpbPart::l);   // 70° across 0°
}
