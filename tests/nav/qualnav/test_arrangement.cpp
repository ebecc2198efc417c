// The arrangement of LPB lines (spec qualnav.md §4): the counts of the paper for n = 3..7 in general
// position, the square's 16, and on random worlds the formula against two independent counts (the
// cells found by sign vector round every crossing, Euler's formula over the cut lines) and against
// dense random sampling; adjacency against "differ in exactly one sign"; degenerate inputs.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "nav/qualnav/topology/arrangement.hpp"

namespace {
namespace qn = neopipe::nav::qualnav;
using Eigen::Vector2d;

std::vector<qn::LandmarkId> iota_ids(std::size_t n) {
  std::vector<qn::LandmarkId> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = i;
  return ids;
}

// n points uniform in a 500 mm square (random positions are in general position almost surely).
std::vector<Vector2d> random_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 500);
  std::vector<Vector2d> p;
  for (std::size_t i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
  return p;
}

std::string message_of(const std::vector<Vector2d>& points, const std::vector<qn::LandmarkId>& ids) {
  try {
    const qn::Arrangement a(ids, points);
    return "no error";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

}  // namespace

TEST(QualnavArrangement, PaperCountsInGeneralPosition) {
  const std::size_t expected[] = {7, 18, 41, 85, 162};
  for (std::size_t n = 3; n <= 7; ++n) {
    EXPECT_EQ(qn::general_position_region_count(n), expected[n - 3]);
    const auto points = random_points(n, 100 + n);
    const qn::Arrangement a(iota_ids(n), points);
    EXPECT_EQ(a.lines().size(), n * (n - 1) / 2);
    EXPECT_EQ(a.region_count(), expected[n - 3]) << n;
    const qn::OrientationRegions regions(a);
    EXPECT_EQ(regions.regions().size(), expected[n - 3]) << n;
    EXPECT_EQ(regions.euler_region_count(), expected[n - 3]) << n;
  }
}

// Fourteen landmarks: 3263 regions by the formula, by the cells found and by Euler's formula.
TEST(QualnavArrangement, FourteenRandomLandmarks) {
  const auto points = random_points(14, 1414);
  const qn::Arrangement a(iota_ids(14), points);
  EXPECT_EQ(a.region_count(), 3263U);
  EXPECT_EQ(qn::general_position_region_count(14), 3263U);
  const qn::OrientationRegions regions(a);
  EXPECT_EQ(regions.regions().size(), 3263U);
  EXPECT_EQ(regions.euler_region_count(), 3263U);
}

TEST(QualnavArrangement, SquareCornersGiveSixteen) {
  const std::vector<Vector2d> square{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  const qn::Arrangement a(iota_ids(4), square);
  EXPECT_EQ(a.lines().size(), 6U);
  // Four corners of multiplicity 3, the centre of multiplicity 2; the sides are parallel.
  ASSERT_EQ(a.crossings().size(), 5U);
  EXPECT_EQ(a.crossings()[4].multiplicity(), 2U);
  EXPECT_NEAR((a.crossings()[4].point - Vector2d(50, 50)).norm(), 0, 1e-9);
  EXPECT_EQ(a.region_count(), 16U);
  const qn::OrientationRegions regions(a);
  EXPECT_EQ(regions.regions().size(), 16U);
  EXPECT_EQ(regions.euler_region_count(), 16U);
}

// A regular hexagon: three main diagonals meet at the centre (m = 3), so general position's formula
// overcounts, but the arrangement's own count still matches its cells.
TEST(QualnavArrangement, ConcurrentLinesMerge) {
  std::vector<Vector2d> hexagon;
  for (int k = 0; k < 6; ++k) {
    const double a = k * std::numbers::pi / 3;
    hexagon.emplace_back(250 + 100 * std::cos(a), 250 + 100 * std::sin(a));
  }
  const qn::Arrangement a(iota_ids(6), hexagon);
  std::size_t centre = 0;
  for (const qn::LineCrossing& c : a.crossings()) {
    if ((c.point - Vector2d(250, 250)).norm() < 1e-6) centre = c.multiplicity();
  }
  EXPECT_EQ(centre, 3U);
  const qn::OrientationRegions regions(a);
  EXPECT_EQ(regions.regions().size(), a.region_count());
  EXPECT_EQ(regions.euler_region_count(), a.region_count());
  EXPECT_LT(a.region_count(), qn::general_position_region_count(6));
}

TEST(QualnavArrangement, RandomWorldsAgreeWithIndependentCounts) {
  int checked = 0;
  int parallel = 0;  // worlds with fewer crossings than general position's
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const std::size_t n = 3 + seed % 6;
    // Snapped to a 125 mm grid: parallel lines and concurrent crossings are common.
    auto points = random_points(n, seed);
    if (seed % 2 == 0) {
      for (Vector2d& p : points) p = (p / 125).array().round() * 125;
    }
    std::unique_ptr<qn::Arrangement> a;
    try {
      a = std::make_unique<qn::Arrangement>(iota_ids(n), points);
    } catch (const std::invalid_argument&) {
      continue;  // a snapped world with a collinear triple
    }
    ++checked;
    parallel += a->region_count() < qn::general_position_region_count(n);
    const qn::OrientationRegions regions(*a);
    EXPECT_EQ(regions.regions().size(), a->region_count()) << "seed " << seed;
    EXPECT_EQ(regions.euler_region_count(), a->region_count()) << "seed " << seed;
    // Every sampled point lies in a region found (or on a line); the interiors are inside their cells.
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-500, 1000);
    std::set<std::size_t> hit;
    for (int i = 0; i < 5000; ++i) {
      const Vector2d p(u(rng), u(rng));
      const auto r = regions.region_of(p);
      ASSERT_TRUE(r) << "seed " << seed << ": " << p.transpose() << " in no region";
      hit.insert(*r);
    }
    EXPECT_LE(hit.size(), a->region_count());
    for (std::size_t r = 0; r < regions.regions().size(); ++r) {
      EXPECT_EQ(regions.region_of(regions.regions()[r].interior), r);
    }
    // Adjacency: exactly the pairs of regions whose sign vectors differ in one LPB.
    std::set<qn::RegionAdjacency> by_signs;
    const auto all = regions.regions();
    for (std::size_t i = 0; i < all.size(); ++i) {
      for (std::size_t j = i + 1; j < all.size(); ++j) {
        std::size_t differ = 0;
        std::size_t line = 0;
        for (std::size_t k = 0; k < all[i].signs.size(); ++k) {
          if (all[i].signs[k] != all[j].signs[k]) {
            ++differ;
            line = k;
          }
        }
        if (differ == 1) by_signs.insert({i, j, line});
      }
    }
    EXPECT_EQ(std::set<qn::RegionAdjacency>(regions.adjacency().begin(), regions.adjacency().end()), by_signs)
        << "seed " << seed;
  }
  EXPECT_GE(checked, 25);
  EXPECT_GE(parallel, 1) << "the snapped worlds should hold parallel LPBs";
}

// A nearly collinear triple (sine 1e-8, above the collinearity threshold): near A its two lines run
// 1e-7 mm apart, so a line across them there makes two crossings closer than the merge distance.
// They are two (lines through A meet only at A), and the counts stay those of general position.
TEST(QualnavArrangement, NearlyCollinearTripleKeepsItsCrossingsApart) {
  const std::vector<Vector2d> points{{0, 0}, {100, 1e-6}, {200, 0}, {10, 50}, {10.0001, -80}};
  const qn::Arrangement a(iota_ids(5), points);
  EXPECT_EQ(a.crossings().size(), 5U + 3U * 5U);
  for (const qn::LineCrossing& c : a.crossings()) {
    if (!c.landmark) {
      EXPECT_EQ(c.multiplicity(), 2U) << c.point.transpose();
    }
  }
  EXPECT_EQ(a.region_count(), 41U);
  const qn::OrientationRegions regions(a);
  EXPECT_EQ(regions.regions().size(), 41U);
  EXPECT_EQ(regions.euler_region_count(), 41U);
}

TEST(QualnavArrangement, TwoLandmarksMakeTwoRegions) {
  const std::vector<Vector2d> two{{0, 0}, {10, 0}};
  const qn::Arrangement a(iota_ids(2), two);
  EXPECT_EQ(a.region_count(), 2U);
  const qn::OrientationRegions regions(a);
  EXPECT_EQ(regions.regions().size(), 2U);
  EXPECT_EQ(regions.euler_region_count(), 2U);
  ASSERT_EQ(regions.adjacency().size(), 1U);
  EXPECT_NE(regions.region_of({5, 3}), regions.region_of({5, -3}));
  EXPECT_FALSE(regions.region_of({5, 0}));
}

TEST(QualnavArrangement, DegenerateInputsNameTheLandmarks) {
  EXPECT_EQ(message_of({{0, 0}}, {4}), "orientation regions need at least two landmarks, got 1");
  EXPECT_EQ(message_of({{0, 0}, {5, 5}, {5, 5}}, {1, 2, 3}),
            "orientation regions: landmarks 2 and 3 coincide, so they span no LPB");
  EXPECT_EQ(message_of({{0, 0}, {10, 10}, {3, 7}, {20, 20}}, {8, 9, 10, 11}),
            "orientation regions: landmarks 8, 9 and 11 are collinear, so their LPB lines coincide");
  EXPECT_EQ(message_of({{0, 0}, {10, 10}}, {6, 6}), "orientation regions: landmark 6 is given twice");
}
