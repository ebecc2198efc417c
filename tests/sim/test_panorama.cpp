// The panoramic sensor's ring image (sim/panorama.hpp): a marble at a known bearing and distance
// covers the columns, rows and area of its disc; discs wrap at the seam; nearer discs cover farther
// ones; the heading turns bearings; R_s cuts; a 400-marble world keeps every identity (ids > 255);
// the tool inside a marble draws nothing for it; noise is seeded; the clearance check; the frame
// source.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "sim/panorama.hpp"
#include "sim/world.hpp"

namespace sim = neopipe::sim;
using Eigen::Vector2d;

namespace {

constexpr double kDegree = std::numbers::pi / 180;

// A world of marbles at (bearing, distance) from (250, 250); no overlap checks (tests place them).
sim::World world_around(const std::vector<std::pair<double, double>>& polar) {
  sim::World w;
  for (const auto& [bearing, distance] : polar) {
    w.objects.emplace_back(250 + distance * std::cos(bearing * kDegree), 250 + distance * std::sin(bearing * kDegree));
  }
  return w;
}

constexpr sim::Pose2 kCentre{250, 250, 0};

double radius_px(double distance, double r_m = 2.5) {
  return std::asin(r_m / distance) / kDegree / sim::kRingDegreesPerPixel;
}

// Pixels whose centre lies within r of (uc, 160), columns wrapped: what the disc must cover.
int lattice_count(double uc, double r) {
  int n = 0;
  for (int v = 0; v < sim::kRingHeight; ++v) {
    for (int u = -sim::kRingWidth; u < 2 * sim::kRingWidth; ++u) {
      if ((u - uc) * (u - uc) + (v - 160.0) * (v - 160.0) <= r * r) ++n;
    }
  }
  return n;
}

std::set<int> values(const cv::Mat& ring) {
  std::set<int> out;
  for (int v = 0; v < ring.rows; ++v) {
    for (int u = 0; u < ring.cols; ++u) {
      if (ring.at<std::int16_t>(v, u) != 0) out.insert(ring.at<std::int16_t>(v, u));
    }
  }
  return out;
}

struct Extent {
  int u0 = 1 << 20, u1 = -1, v0 = 1 << 20, v1 = -1, area = 0;
};
Extent extent_of(const cv::Mat& ring, int value) {
  Extent e;
  for (int v = 0; v < ring.rows; ++v) {
    for (int u = 0; u < ring.cols; ++u) {
      if (ring.at<std::int16_t>(v, u) != value) continue;
      e.u0 = std::min(e.u0, u);
      e.u1 = std::max(e.u1, u);
      e.v0 = std::min(e.v0, v);
      e.v1 = std::max(e.v1, v);
      ++e.area;
    }
  }
  return e;
}

TEST(Panorama, ColumnsAreBearingsOfATenthOfADegree) {
  EXPECT_DOUBLE_EQ(sim::ring_column(0.05), 0.0);
  EXPECT_DOUBLE_EQ(sim::ring_column(359.95), 3599.0);
  EXPECT_NEAR(sim::ring_bearing_deg(0), 0.05, 1e-12);
  EXPECT_NEAR(sim::ring_bearing_deg(3599.5), 0.0, 1e-9);
  EXPECT_NEAR(sim::ring_bearing_deg(-1), 359.95, 1e-9);
}

TEST(Panorama, OneMarbleCoversItsDiscsColumnsRowsAndArea) {
  for (const auto& [bearing, distance] : {std::pair{30.0, 50.0}, {200.0, 17.0}, {123.4, 300.0}, {271.0, 599.0}}) {
    SCOPED_TRACE("bearing " + std::to_string(bearing) + ", distance " + std::to_string(distance));
    const sim::World w = world_around({{bearing, distance}});
    const sim::Ring ring = sim::render_ring(w, kCentre, {});
    ASSERT_EQ(ring.image.type(), CV_16SC1);
    ASSERT_EQ(ring.image.size(), cv::Size(3600, 320));
    EXPECT_EQ(ring.discs, 1);
    EXPECT_EQ(values(ring.image), std::set<int>{1});
    const double uc = bearing / 0.1 - 0.5;
    const double r = radius_px(distance);
    const Extent e = extent_of(ring.image, 1);
    EXPECT_EQ(e.u0, static_cast<int>(std::ceil(uc - r)));
    EXPECT_EQ(e.u1, static_cast<int>(std::floor(uc + r)));
    EXPECT_EQ(e.v0, 160 - static_cast<int>(std::floor(r)));
    EXPECT_EQ(e.v1, 160 + static_cast<int>(std::floor(r)));
    EXPECT_EQ(e.area, lattice_count(uc, r));
    // Within a pixel of the radius all round: the area of a disc of radius r - 1/2 .. r + 1/2.
    EXPECT_GE(e.area, std::numbers::pi * (r - 0.5) * (r - 0.5));
    EXPECT_LE(e.area, std::numbers::pi * (r + 0.5) * (r + 0.5));
  }
}

TEST(Panorama, DiscsWrapAcrossTheSeam) {
  const double distance = 40;
  const sim::World w = world_around({{0.0, distance}});
  const cv::Mat ring = sim::render_ring(w, kCentre, {}).image;
  const double r = radius_px(distance);
  const int reach = static_cast<int>(std::floor(r - 0.5));  // centre at column -0.5
  for (int u = 0; u < 3600; ++u) {
    const bool inside = u <= reach || u >= 3600 - reach - 1;
    EXPECT_EQ(ring.at<std::int16_t>(160, u) != 0, inside) << "column " << u;
  }
  EXPECT_EQ(cv::countNonZero(ring), lattice_count(-0.5, r));
}

TEST(Panorama, NearerDiscsCoverFartherOnes) {
  // Same bearing: the farther disc is smaller and hidden entirely.
  const sim::World hidden = world_around({{90.0, 40.0}, {90.0, 20.0}});
  const cv::Mat a = sim::render_ring(hidden, kCentre, {}).image;
  EXPECT_EQ(values(a), std::set<int>{2});
  // A little aside: both identities, the farther one's visible part smaller than its disc; the
  // nearer one whole. Given in either order, the same image.
  const sim::World aside = world_around({{95.0, 40.0}, {90.0, 20.0}});
  const sim::World swapped = world_around({{90.0, 20.0}, {95.0, 40.0}});
  const cv::Mat b = sim::render_ring(aside, kCentre, {}).image;
  EXPECT_EQ(values(b), (std::set<int>{1, 2}));
  EXPECT_LT(extent_of(b, 1).area, lattice_count(95 / 0.1 - 0.5, radius_px(40)));
  EXPECT_EQ(extent_of(b, 2).area, lattice_count(90 / 0.1 - 0.5, radius_px(20)));
  cv::Mat c = sim::render_ring(swapped, kCentre, {}).image;
  c.setTo(7, c == 1);
  c.setTo(1, c == 2);
  c.setTo(2, c == 7);
  EXPECT_EQ(cv::countNonZero(b != c), 0);
}

TEST(Panorama, TheHeadingTurnsBearings) {
  const sim::World w = world_around({{60.0, 80.0}, {200.0, 30.0}, {359.0, 120.0}});
  for (const double heading : {30.0, -45.0, 181.0}) {
    const sim::Pose2 turned{250, 250, heading * kDegree};
    const auto in_view = sim::marbles_in_view(w, turned, 600);
    ASSERT_EQ(in_view.size(), 3U);
    const double expected[] = {60, 200, 359};
    const cv::Mat ring = sim::render_ring(w, turned, {}).image;
    for (std::size_t i = 0; i < 3; ++i) {
      const double want = std::fmod(expected[i] - heading + 720, 360);
      EXPECT_NEAR(in_view[i].bearing_deg, want, 1e-9);
      // The disc's columns are centred on the turned bearing.
      const Extent e = extent_of(ring, static_cast<int>(i) + 1);
      const double mid = e.u1 - e.u0 < 1800 ? (e.u0 + e.u1) / 2.0 : (e.u0 + e.u1 + 3600) / 2.0;
      EXPECT_NEAR(std::fmod(sim::ring_bearing_deg(mid) - want + 540, 360) - 180, 0, 0.1) << "marble " << i;
    }
  }
}

TEST(Panorama, OnlyMarblesWithinRangeAreSeen) {
  const sim::World w = world_around({{10.0, 599.0}, {20.0, 601.0}, {30.0, 250.0}});
  EXPECT_EQ(values(sim::render_ring(w, kCentre, {}).image), (std::set<int>{1, 3}));
  sim::PanoramaSettings near;
  near.range_mm = 300;
  EXPECT_EQ(values(sim::render_ring(w, kCentre, near).image), std::set<int>{3});
}

TEST(Panorama, ADenseWorldKeepsEveryIdentity) {
  sim::WorldRequest q;
  q.objects = 400;
  q.seed = 7;
  const sim::World w = sim::generate_world(q);
  const sim::Pose2 tool{250.5, 249.5, 0.3};
  ASSERT_TRUE(sim::keeps_clear(w, {tool.x, tool.y}, 0));
  const auto in_view = sim::marbles_in_view(w, tool, 600);
  EXPECT_EQ(in_view.size(), 400U);  // R_s reaches every corner from the centre
  const auto start = std::chrono::steady_clock::now();
  constexpr int kFrames = 50;
  sim::Ring ring;
  for (int i = 0; i < kFrames; ++i) ring = sim::render_ring(w, tool, {});
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kFrames;
  std::cout << "[ measure ] 400-marble ring: " << ms << " ms per frame\n";
  const std::set<int> seen = values(ring.image);
  EXPECT_GT(*seen.rbegin(), 256);
  for (const int v : seen) EXPECT_TRUE(v >= 1 && v <= 400) << v;
  // Every marble whose disc no nearer disc reaches is there, with its own value.
  int unoccluded = 0;
  for (const auto& m : in_view) {
    bool covered = false;
    for (const auto& o : in_view) {
      const double gap = std::abs(std::fmod(o.bearing_deg - m.bearing_deg + 540, 360) - 180);
      covered = covered || (o.distance_mm < m.distance_mm && gap < o.angular_radius_deg + m.angular_radius_deg + 0.2);
    }
    if (covered) continue;
    ++unoccluded;
    EXPECT_EQ(seen.count(static_cast<int>(m.id) + 1), 1U) << "marble " << m.id;
  }
  EXPECT_GT(unoccluded, 20);
  EXPECT_GT(seen.size(), 100U);
  // Nearer marbles hide most of the world from one place; from a few places every identity shows.
  std::set<int> union_seen = seen;
  sim::Random where(9);
  for (int looks = 0; looks < 40;) {
    const sim::Pose2 p{where.uniform(20, 480), where.uniform(20, 480), 0};
    if (!sim::keeps_clear(w, {p.x, p.y})) continue;
    ++looks;
    const std::set<int> s = values(sim::render_ring(w, p, {}).image);
    union_seen.insert(s.begin(), s.end());
  }
  EXPECT_EQ(union_seen.size(), 400U);
}

TEST(Panorama, AMarbleTheToolIsInsideIsNotDrawn) {
  sim::World w = world_around({{0.0, 1.0}, {90.0, 50.0}});
  const sim::Ring ring = sim::render_ring(w, kCentre, {});
  EXPECT_EQ(ring.inside, std::vector<std::uint32_t>{0});
  EXPECT_EQ(values(ring.image), std::set<int>{2});
}

TEST(Panorama, NoiseIsSeededAndMovesDiscsAlongTheRow) {
  const sim::World w = world_around({{45.0, 100.0}, {135.0, 100.0}});
  sim::PanoramaSettings s;
  s.bearing_noise_deg = 2;
  sim::Random a(3);
  sim::Random b(3);
  sim::Random c(4);
  const cv::Mat ra = sim::render_ring(w, kCentre, s, &a).image;
  EXPECT_EQ(cv::countNonZero(ra != sim::render_ring(w, kCentre, s, &b).image), 0);
  EXPECT_GT(cv::countNonZero(ra != sim::render_ring(w, kCentre, s, &c).image), 0);
  EXPECT_GT(cv::countNonZero(ra != sim::render_ring(w, kCentre, {}).image), 0);
  // Rows stay: only bearings are jittered.
  EXPECT_EQ(extent_of(ra, 1).v0, 160 - static_cast<int>(std::floor(radius_px(100))));
  // Without a random source there is no noise.
  EXPECT_EQ(cv::countNonZero(sim::render_ring(w, kCentre, s).image != sim::render_ring(w, kCentre, {}).image), 0);
}

TEST(Panorama, RefusesWorldsItCannotLabelAndBadSettings) {
  sim::World big;
  big.objects.assign(32768, Vector2d(1, 1));
  EXPECT_THROW(sim::render_ring(big, kCentre, {}), std::invalid_argument);
  sim::PanoramaSettings s;
  s.range_mm = 0;
  EXPECT_THROW(sim::render_ring(sim::World{}, kCentre, s), std::invalid_argument);
  s = {};
  s.bearing_noise_deg = -1;
  EXPECT_THROW(sim::PanoramicSensor(sim::World{}, s), std::invalid_argument);
}

TEST(Panorama, ClearanceIsFromTheMarblesSurface) {
  const sim::World w = world_around({{0.0, 20.0}, {180.0, 13.0}});
  const auto nearest = sim::nearest_surface(w, {250, 250});
  ASSERT_TRUE(nearest.has_value());
  EXPECT_EQ(nearest->id, 1U);
  EXPECT_NEAR(nearest->gap_mm, 10.5, 1e-9);
  EXPECT_TRUE(sim::keeps_clear(w, {250, 250}));
  EXPECT_FALSE(sim::keeps_clear(w, {249, 250}));
  EXPECT_FALSE(sim::nearest_surface(sim::World{}, {0, 0}).has_value());
  EXPECT_TRUE(sim::keeps_clear(sim::World{}, {0, 0}));
}

TEST(Panorama, TheSensorIsAFrameSourceAndACompass) {
  const sim::World w = world_around({{45.0, 100.0}});
  sim::PanoramicSensor sensor(w, {});
  sim::Pose2 pose = kCentre;
  const auto source = sim::panoramic_camera_source(sensor, [&] { return pose; });
  const auto f0 = source->next();
  ASSERT_TRUE(f0.has_value());
  EXPECT_EQ(f0->index, 0);
  EXPECT_EQ(f0->image.type(), CV_16SC1);
  EXPECT_EQ(cv::countNonZero(f0->image != sim::render_ring(w, pose, {}).image), 0);
  pose.theta = 90 * kDegree;
  const auto f1 = source->next();
  EXPECT_EQ(f1->index, 1);
  EXPECT_EQ(cv::countNonZero(f1->image != sim::render_ring(w, pose, {}).image), 0);
  // The compass: the heading with a 1° error, unbiased.
  double sum = 0;
  double sum_sq = 0;
  constexpr int kReads = 4000;
  for (int i = 0; i < kReads; ++i) {
    const double e = std::fmod(sensor.compass_deg(pose) - 90 + 540, 360) - 180;
    sum += e;
    sum_sq += e * e;
  }
  const double mean = sum / kReads;
  EXPECT_NEAR(mean, 0, 0.06);  // 4 standard errors
  EXPECT_NEAR(std::sqrt(sum_sq / kReads - mean * mean), 1.0, 0.05);
}

}  // namespace
