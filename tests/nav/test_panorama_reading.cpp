// Readings of the panoramic sensor (nav/common/panorama_reading.hpp) from rings the simulator draws
// (sim/panorama.hpp), against the truth: bearings within e of the true ones and unbiased over many
// random poses (with and without configured noise), true ranges inside the range interval for
// unhidden marbles, the seam's two halves joined, the range order of well-separated marbles, the
// engine's graph giving the kernel's table, and the two libraries agreeing on the ring's geometry.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <numbers>
#include <vector>

#include "kernels/value_blobs.hpp"
#include "nav/common/panorama_reading.hpp"
#include "sim/panorama.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace nav = neopipe::nav;
namespace sim = neopipe::sim;
namespace kn = neopipe::kernels;

namespace {

constexpr double kDegree = std::numbers::pi / 180;

double angle_diff(double a, double b) {
  return std::fmod(a - b + 540.0, 360.0) - 180.0;
}

sim::World world_around(const std::vector<std::pair<double, double>>& polar) {
  sim::World w;
  for (const auto& [bearing, distance] : polar) {
    w.objects.emplace_back(250 + distance * std::cos(bearing * kDegree), 250 + distance * std::sin(bearing * kDegree));
  }
  return w;
}

// Whether any nearer marble's disc comes within `margin` degrees of m's.
bool hidden_in_part(const sim::MarbleInView& m, const std::vector<sim::MarbleInView>& all, double margin) {
  for (const auto& o : all) {
    if (o.distance_mm < m.distance_mm &&
        std::abs(angle_diff(o.bearing_deg, m.bearing_deg)) < o.angular_radius_deg + m.angular_radius_deg + margin) {
      return true;
    }
  }
  return false;
}

struct Statistics {
  int poses = 0;
  int samples = 0;         ///< unhidden marbles in view, over all poses
  int within_e = 0;        ///< of which with the bearing within e
  int range_inside = 0;    ///< of which with the true range inside the interval
  int missing = 0;         ///< unhidden marbles without a sighting
  int hidden_flagged = 0;  ///< sightings showing under 80 % of their disc, flagged partial
  int hidden = 0;
  int pairs = 0;          ///< unhidden pairs whose true ranges differ by more than 25 %
  int pairs_ordered = 0;  ///< of which ordered rightly by the estimates
  double sum = 0;
  double sum_sq = 0;
  double worst = 0;
};

Statistics random_poses(double noise_deg, int poses, std::uint64_t seed) {
  sim::WorldRequest q;
  q.objects = 100;
  q.seed = seed;
  const sim::World world = sim::generate_world(q);
  sim::PanoramaSettings settings;
  settings.bearing_noise_deg = noise_deg;
  settings.seed = seed;
  sim::PanoramicSensor sensor(world, settings);
  nav::PanoramaReader reader({world.marble_diameter / 2, noise_deg});
  sim::Random where(seed + 99);
  Statistics s;
  const double margin = 0.2 + 5 * noise_deg;
  while (s.poses < poses) {
    const sim::Pose2 tool{where.uniform(15, 485), where.uniform(15, 485),
                          where.uniform(-std::numbers::pi, std::numbers::pi)};
    if (!sim::keeps_clear(world, {tool.x, tool.y})) continue;
    ++s.poses;
    const auto truth = sim::marbles_in_view(world, tool, settings.range_mm);
    const auto sightings = reader.read(sensor.ring(tool).image);
    std::map<std::uint32_t, const nav::PanoramaSighting*> by_id;
    for (const auto& r : sightings) by_id[r.id] = &r;
    std::vector<std::pair<double, double>> unhidden;  // (true, estimated) ranges
    for (const auto& m : truth) {
      const auto it = by_id.find(m.id);
      if (it != by_id.end()) {
        const double full = std::numbers::pi * std::pow(m.angular_radius_deg / 0.1, 2);
        if (m.angular_radius_deg >= 0.3 && static_cast<double>(it->second->area_px) < 0.8 * full) {
          ++s.hidden;
          s.hidden_flagged += it->second->partial ? 1 : 0;
        }
      }
      if (hidden_in_part(m, truth, margin)) continue;
      ++s.samples;
      if (it == by_id.end()) {
        ++s.missing;
        continue;
      }
      const nav::PanoramaSighting& r = *it->second;
      const double e = angle_diff(r.bearing_deg, m.bearing_deg);
      s.sum += e;
      s.sum_sq += e * e;
      s.worst = std::max(s.worst, std::abs(e));
      s.within_e += std::abs(e) <= r.bearing_error_deg ? 1 : 0;
      s.range_inside += (m.distance_mm >= r.range_lo_mm && m.distance_mm <= r.range_hi_mm) ? 1 : 0;
      unhidden.emplace_back(m.distance_mm, r.range_mm);
    }
    for (std::size_t i = 0; i < unhidden.size(); ++i) {
      for (std::size_t j = i + 1; j < unhidden.size(); ++j) {
        const auto& [ti, ei] = unhidden[i];
        const auto& [tj, ej] = unhidden[j];
        if (std::max(ti, tj) < 1.25 * std::min(ti, tj)) continue;
        ++s.pairs;
        s.pairs_ordered += (ti < tj) == (ei < ej) ? 1 : 0;
      }
    }
  }
  return s;
}

void report(const char* what, const Statistics& s) {
  const double mean = s.sum / s.samples;
  std::cout << "[ measure ] " << what << ": " << s.poses << " poses, " << s.samples << " unhidden marbles; bearing "
            << "error mean " << mean << " deg, sd " << std::sqrt(s.sum_sq / s.samples - mean * mean) << " deg, worst "
            << s.worst << " deg, within e " << 100.0 * s.within_e / s.samples << " %; true range inside the interval "
            << 100.0 * s.range_inside / s.samples << " %; pairs 25 % apart ordered "
            << 100.0 * s.pairs_ordered / s.pairs << " % of " << s.pairs << "; discs under 80 % visible flagged partial "
            << s.hidden_flagged << " of " << s.hidden << "\n";
}

TEST(PanoramaReading, BearingsAndRangesOverRandomPosesWithoutNoise) {
  const Statistics s = random_poses(0, 200, 11);
  report("noise 0", s);
  ASSERT_GT(s.samples, 5000);
  EXPECT_EQ(s.missing, 0);
  // Without noise every unhidden bearing lies within e = 0.2°. The mean's standard error is below
  // 0.001° here, so a bias of 0.01° (a tenth of a pixel) would fail.
  EXPECT_EQ(s.within_e, s.samples);
  EXPECT_LT(std::abs(s.sum / s.samples), 0.01);
  EXPECT_GE(s.range_inside, 0.99 * s.samples);
  EXPECT_GE(s.pairs_ordered, 0.99 * s.pairs);
  // The flag is a heuristic on the blob table (boxes touching a larger disc's, width short of
  // height): 3729 of 3730 such discs here.
  EXPECT_GE(s.hidden_flagged, 0.995 * s.hidden);
}

TEST(PanoramaReading, BearingsWithConfiguredNoise) {
  const double sigma = 0.3;
  const Statistics s = random_poses(sigma, 200, 12);
  report("noise 0.3 deg", s);
  ASSERT_GT(s.samples, 5000);
  const double mean = s.sum / s.samples;
  const double sd = std::sqrt(s.sum_sq / s.samples - mean * mean);
  // Standard error of the mean about 0.3 / sqrt(5000) = 0.004°: a 0.1° bias is 20 of them.
  EXPECT_LT(std::abs(mean), 0.02);
  EXPECT_NEAR(sd, sigma, 0.03);
  // e = 0.2° + 0.3° is 1.67 sd of the noise: about 90 % within it.
  EXPECT_GE(s.within_e, 0.85 * s.samples);
  EXPECT_GE(s.range_inside, 0.99 * s.samples);
}

TEST(PanoramaReading, TheSeamsTwoHalvesAreOneSighting) {
  for (const double bearing : {0.0, 0.13, 359.91}) {
    SCOPED_TRACE(bearing);
    const sim::World across = world_around({{bearing, 30.0}});
    nav::PanoramaReader reader({2.5, 0});
    const cv::Mat ring = sim::render_ring(across, {250, 250, 0}, {}).image;
    ASSERT_EQ(kn::extract_value_blobs(ring, kn::Connectivity::eight).size(), 2U);
    const auto sightings = reader.read(ring);
    ASSERT_EQ(sightings.size(), 1U);
    EXPECT_EQ(sightings[0].id, 0U);
    EXPECT_EQ(sightings[0].pieces, 2);
    EXPECT_FALSE(sightings[0].partial);
    EXPECT_LT(std::abs(angle_diff(sightings[0].bearing_deg, bearing)), 0.2);
    // The whole disc's area: the same marble away from the seam, at the same fraction of a pixel.
    const sim::World away = world_around({{bearing + 180, 30.0}});
    const auto whole = reader.read(sim::render_ring(away, {250, 250, 0}, {}).image);
    ASSERT_EQ(whole.size(), 1U);
    EXPECT_NEAR(static_cast<double>(sightings[0].area_px), static_cast<double>(whole[0].area_px), 2);
    EXPECT_NEAR(sightings[0].range_mm, whole[0].range_mm, 0.1);
  }
}

TEST(PanoramaReading, RangeOrderOfWellSeparatedMarbles) {
  // ids 0..4 at distances 250, 15, 590, 40, 100 (each 2.5x the next nearer), spread in bearing.
  const sim::World w = world_around({{10, 250}, {100, 15}, {190, 590}, {250, 40}, {320, 100}});
  nav::PanoramaReader reader({2.5, 0});
  const auto sightings = reader.read(sim::render_ring(w, {250, 250, 0.7}, {}).image);
  ASSERT_EQ(sightings.size(), 5U);
  const auto nearest = nav::nearest_by_range(sightings, 18);
  std::vector<std::uint32_t> order(nearest.size());
  std::transform(nearest.begin(), nearest.end(), order.begin(), [](const auto& s) { return s.id; });
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 3, 4, 0, 2}));
  const auto three = nav::nearest_by_range(sightings, 3);
  ASSERT_EQ(three.size(), 3U);
  EXPECT_EQ(three[2].id, 4U);
  for (const auto& s : sightings) {
    const double truth = std::vector<double>{250, 15, 590, 40, 100}[s.id];
    EXPECT_GE(truth, s.range_lo_mm);
    EXPECT_LE(truth, s.range_hi_mm);
    EXPECT_NEAR(s.range_hi_mm / s.range_lo_mm, 2.25, 1e-12);
    EXPECT_DOUBLE_EQ(s.bearing_error_deg, 0.2);
  }
}

TEST(PanoramaReading, TheGraphGivesTheKernelsTableAndBlobsOfValueZeroOrLessAreIgnored) {
  sim::WorldRequest q;
  q.objects = 400;
  q.seed = 3;
  const sim::World w = sim::generate_world(q);
  const cv::Mat ring = sim::render_ring(w, {240, 260, 1.0}, {}).image;
  nav::PanoramaReader reader({2.5, 0.1});
  const auto via_graph = reader.read(ring);
  const auto direct = nav::sightings_from_blobs(kn::extract_value_blobs(ring, kn::Connectivity::eight), {2.5, 0.1});
  ASSERT_EQ(via_graph.size(), direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(via_graph[i].id, direct[i].id);
    EXPECT_EQ(via_graph[i].bearing_deg, direct[i].bearing_deg);
    EXPECT_EQ(via_graph[i].area_px, direct[i].area_px);
    EXPECT_EQ(via_graph[i].partial, direct[i].partial);
    if (i > 0) {
      EXPECT_LT(direct[i - 1].id, direct[i].id);
    }
  }
  EXPECT_GT(via_graph.back().id, 255U);
  kn::Blob negative;
  negative.area = 5;
  negative.value = -3;
  EXPECT_TRUE(nav::sightings_from_blobs({negative}, {}).empty());
  EXPECT_THROW(reader.read(cv::Mat(320, 3600, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
}

// What docs/panorama.md quotes: one frame's render and read, from the middle of the 400-marble world
// (every marble within R_s) and of the 100-marble one. Printed, not held to a bound: the machine is
// shared.
TEST(PanoramaReading, RenderAndReadTimePerFrame) {
  for (const int objects : {100, 400}) {
    sim::WorldRequest q;
    q.objects = objects;
    q.seed = 7;
    const sim::World w = sim::generate_world(q);
    sim::PanoramicSensor sensor(w, {});
    nav::PanoramaReader reader({2.5, 0});
    const sim::Pose2 tool{220, 250, 30 * kDegree};
    constexpr int kFrames = 200;
    double render_ms = 0;
    double read_ms = 0;
    std::size_t seen = 0;
    for (int i = 0; i < kFrames; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat ring = sensor.ring(tool).image;
      const auto t1 = std::chrono::steady_clock::now();
      seen = reader.read(ring).size();
      const auto t2 = std::chrono::steady_clock::now();
      render_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
      read_ms += std::chrono::duration<double, std::milli>(t2 - t1).count();
    }
    std::cout << "[ measure ] " << objects << " marbles, " << seen << " seen: render " << render_ms / kFrames
              << " ms, read " << read_ms / kFrames << " ms per frame\n";
    EXPECT_GT(seen, 0U);
  }
}

TEST(PanoramaReading, AgreesWithTheSimulatorOnTheRingsGeometry) {
  EXPECT_EQ(nav::kPanoramaWidth, sim::kRingWidth);
  EXPECT_EQ(nav::kPanoramaDegreesPerPixel, sim::kRingDegreesPerPixel);
}

}  // namespace
