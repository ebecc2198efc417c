// Qualnav's metric level against the worked examples of qualnav.md §10: constant-angle loci and
// the localization of a sensor at (50, 50) between L1 (0,0) and L2 (100,0); the loci formulas
// against each other; localization shrinking as landmarks are added; viewframe headings against
// the true displacement.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "nav/qualnav/metric/localization.hpp"
#include "nav/qualnav/metric/viewframe.hpp"
#include "nav/qualnav/metric/viewframe_heading.hpp"

namespace {

namespace q = neopipe::nav::qualnav;
using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;

// The viewframe a sensor at `p` with heading `heading` sees of `landmarks` (ids 0..), bearings
// exact, intervals [r / f, r · f] around the true range r.
q::Viewframe view_from(const Vector2d& p, double heading, const std::vector<Vector2d>& landmarks, double error,
                       double factor) {
  std::vector<q::ViewedLandmark> v;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const Vector2d d = landmarks[i] - p;
    const double r = d.norm();
    v.push_back({static_cast<q::LandmarkId>(i), std::atan2(d.y(), d.x()) - heading, error, r, r / factor, r * factor});
  }
  return q::make_viewframe(v, heading);
}

TEST(ConstantAngleLocus, WorkedExamples) {
  const q::Circle right = q::constant_angle_locus(2, kPi / 2);
  EXPECT_NEAR(right.centre.x(), 1, 1e-12);
  EXPECT_NEAR(right.centre.y(), 0, 1e-12);
  EXPECT_NEAR(right.radius, 1, 1e-12);
  const q::Circle thirty = q::constant_angle_locus(2, kPi / 6);
  EXPECT_NEAR(thirty.centre.x(), 1, 1e-12);
  EXPECT_NEAR(thirty.centre.y(), std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(thirty.radius, 2, 1e-12);
}

TEST(ConstantAngleLocus, EveryPointOnItSeesThePairUnderTheta) {
  const double s = 80;
  for (const double theta : {0.3, 1.0, kPi / 2, 2.5}) {
    const q::Circle c = q::constant_angle_locus(s, theta);
    for (double phi = 0.1; phi < kPi - theta; phi += 0.2) {
      // The observer at angle φ at L1, range from the formula; it lies on the circle, sees θ, and
      // locus_angle recovers φ from its two ranges.
      const double r1 = q::locus_range(s, theta, phi);
      const Vector2d p = r1 * Vector2d(std::cos(phi), std::sin(phi));
      EXPECT_NEAR((p - c.centre).norm(), c.radius, 1e-9);
      const Vector2d u = -p;
      const Vector2d v = Vector2d(s, 0) - p;
      EXPECT_NEAR(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)), theta, 1e-9);
      EXPECT_NEAR(q::locus_angle(r1, v.norm(), theta), phi, 1e-9);
    }
  }
}

TEST(Localization, TightIntervalsPinTheSensorWithin3Mm) {
  const std::vector<Vector2d> l = {{0, 0}, {100, 0}};
  const q::Viewframe v = view_from({50, 50}, 0.4, l, 0.2 * kPi / 180, 1.01);
  q::LocalizationOptions o;
  o.keep_cells = true;
  const q::Localization loc = q::localize(v, {{0, l[0]}, {1, l[1]}}, o);
  ASSERT_FALSE(loc.empty());
  for (const Vector2d& c : loc.cells) EXPECT_LE((c - Vector2d(50, 50)).norm(), 3.0) << c.transpose();
}

TEST(Localization, WideIntervalsHoldTheSensorAndCentreOnIt) {
  const std::vector<Vector2d> l = {{0, 0}, {100, 0}};
  const q::Viewframe v = view_from({50, 50}, -1.2, l, 0.1, 1.5);
  q::LocalizationOptions o;
  o.keep_cells = true;
  const q::Localization loc = q::localize(v, {{0, l[0]}, {1, l[1]}}, o);
  ASSERT_FALSE(loc.empty());
  bool holds = false;
  for (const Vector2d& c : loc.cells) holds = holds || (c - Vector2d(50, 50)).norm() <= 0.75;
  EXPECT_TRUE(holds);
  EXPECT_NEAR(loc.centroid.x(), 50, 1);
  // The coarse-to-fine search finds every cell an exhaustive scan finds.
  std::size_t exhaustive = 0;
  for (int y = -200; y <= 200; ++y) {
    for (int x = -200; x <= 300; ++x) {
      const Vector2d p(x, y);
      const double d0 = p.norm();
      const double d1 = (p - l[1]).norm();
      const q::ViewedLandmark& a = *v.find(0);
      const q::ViewedLandmark& b = *v.find(1);
      if (d0 < a.range_lo || d0 > a.range_hi || d1 < b.range_lo || d1 > b.range_hi) continue;
      const Vector2d u = l[0] - p;
      const Vector2d w = l[1] - p;
      const double seen = std::atan2(u.x() * w.y() - u.y() * w.x(), u.dot(w));
      if (std::abs(q::wrap_angle(seen - q::angle_between(a, b))) <= a.error + b.error) ++exhaustive;
    }
  }
  EXPECT_EQ(loc.count, exhaustive);
}

TEST(Localization, ShrinksAsLandmarksAreAdded) {
  const std::vector<Vector2d> l = {{0, 0}, {100, 0}, {120, 90}, {-40, 110}, {60, 160}};
  const Vector2d sensor(50, 50);
  const q::Viewframe v = view_from(sensor, 0, l, 0.1, 1.5);
  std::size_t previous = 0;
  for (std::size_t n = 2; n <= l.size(); ++n) {
    q::FramePositions known;
    for (std::size_t i = 0; i < n; ++i) known[static_cast<q::LandmarkId>(i)] = l[i];
    const q::Localization loc = q::localize(v, known);
    ASSERT_FALSE(loc.empty()) << n;
    // docs/qualnav-navigation.md quotes these (50 % ranges, e = 0.1 rad).
    std::cout << "landmarks " << n << ": " << loc.area_mm2() << " mm2, centroid " << loc.centroid.transpose()
              << ", box " << (loc.max - loc.min).transpose() << " mm\n";
    if (n > 2) {
      EXPECT_LT(loc.count, previous) << n;
    }
    previous = loc.count;
  }
}

TEST(ViewframeHeading, PointsFromOneViewframeToTheOther) {
  const std::vector<Vector2d> l = {{0, 0}, {100, 0}, {160, 120}, {-30, 140}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const Vector2d a(30 + 60 * u(rng), 30 + 60 * u(rng));
    const double angle = 2 * kPi * u(rng);
    const Vector2d b = a + (10 + 20 * u(rng)) * Vector2d(std::cos(angle), std::sin(angle));  // 10-30 mm on
    const double heading_a = 2 * kPi * u(rng);
    const q::Viewframe va = view_from(a, heading_a, l, 0.2 * kPi / 180, 1.05);
    const q::Viewframe vb = view_from(b, 2 * kPi * u(rng), l, 0.2 * kPi / 180, 1.05);
    q::FrameScales scales;
    scales.add(va);
    scales.add(vb);
    const auto h = q::viewframe_heading(va, vb, scales);
    ASSERT_TRUE(h.has_value());
    const Vector2d truth = b - a;
    EXPECT_NEAR(h->distance, truth.norm(), 0.15 * truth.norm() + 3);
    // In a's sensor frame the true move has bearing atan2(truth) − heading_a.
    const double want = std::atan2(truth.y(), truth.x()) - heading_a;
    // Two centroids each within a few mm of the truth: the bearing within what that allows.
    const double tolerance = std::atan2(0.1 * truth.norm() + 3, truth.norm());
    EXPECT_LT(std::abs(q::wrap_angle(h->sensor_bearing - want)), tolerance) << trial << " " << truth.norm();
  }
}

TEST(ViewframeHeading, SameViewIsNoMove) {
  const std::vector<Vector2d> l = {{0, 0}, {100, 0}, {160, 120}};
  const q::Viewframe v = view_from({40, 60}, 1, l, 0.003, 1.5);
  q::FrameScales scales;
  scales.add(v);
  const auto h = q::viewframe_heading(v, v, scales);
  ASSERT_TRUE(h.has_value());
  EXPECT_NEAR(h->distance, 0, 1e-9);
}

}  // namespace
