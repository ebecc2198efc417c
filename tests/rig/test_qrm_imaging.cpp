// The imaging tour of QRM map building (rig/qrm_imaging.hpp): on a noiseless sensor the map never
// loses a true state, the tour is deterministic for its seeds, and imaging positions keep clear.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "nav/qrm/edc.hpp"
#include "rig/qrm_imaging.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {
namespace {

namespace qrm = nav::qrm;

sim::World small_world(int marbles, std::uint64_t seed) {
  sim::WorldRequest request;
  request.objects = marbles;
  request.seed = seed;
  return sim::generate_world(request);
}

// Every relation of every triple of the map still holds the state of the true positions.
int lost_true_states(const qrm::RelationalMap& map, const sim::World& world) {
  int lost = 0;
  const auto& ids = map.landmarks();
  for (const qrm::LandmarkId p : ids) {
    for (const qrm::LandmarkId q : ids) {
      for (const qrm::LandmarkId r : ids) {
        if (p == q || q == r || p == r) continue;
        const qrm::State truth = qrm::classify(world.objects[p], world.objects[q], world.objects[r]);
        if (truth == 0) continue;  // degenerate: no state to keep
        if (!map.relation(p, q, r).contains(truth)) ++lost;
      }
    }
  }
  return lost;
}

TEST(QrmImaging, NoiselessSensorNeverLosesATrueState) {
  for (const std::uint64_t seed : {1U, 2U, 3U}) {
    const sim::World world = small_world(14, seed);
    QrmImagingSettings settings;
    settings.heading_seed = seed;
    settings.observation.nearest = 10;
    qrm::RelationalMap map;
    const auto positions = random_imaging_positions(world, 8, seed);
    const auto reports = qrm_imaging_tour(world, positions, settings, map);
    ASSERT_EQ(reports.size(), 8U);
    int inconsistent = 0;
    std::size_t refined = 0;
    for (const QrmImageReport& r : reports) {
      inconsistent += static_cast<int>(r.fused.inconsistent);
      refined += r.fused.refined;
      EXPECT_LE(r.fused.landmarks, 10U);
    }
    EXPECT_EQ(inconsistent, 0) << "seed " << seed;
    EXPECT_GT(refined, 0U);
    EXPECT_GE(map.size(), 10U);
    EXPECT_EQ(lost_true_states(map, world), 0) << "seed " << seed;
  }
}

TEST(QrmImaging, SightingsAreInTheSensorFrame) {
  // A world of three marbles seen from one point with two zero directions: bearings differ by the
  // turn (the map gets no compass), ranges are the same.
  sim::World world;
  world.objects = {{100, 100}, {300, 120}, {200, 400}};
  QrmImaging imaging(world, {});
  const Eigen::Vector2d at{200, 200};
  const auto a = imaging.sightings(at, 0);
  const auto b = imaging.sightings(at, 1.0);
  ASSERT_EQ(a.size(), 3U);
  ASSERT_EQ(b.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a[i].id, b[i].id);
    const double turn = std::remainder(a[i].bearing - b[i].bearing - 1.0, 2 * std::numbers::pi);
    EXPECT_NEAR(turn, 0, 0.002);
    EXPECT_NEAR(a[i].range, b[i].range, 0.05 * a[i].range);
    const Eigen::Vector2d d = world.objects[a[i].id] - at;
    EXPECT_NEAR(std::remainder(a[i].bearing - std::atan2(d.y(), d.x()), 2 * std::numbers::pi), 0, 0.002);
  }
}

TEST(QrmImaging, SameSeedsSameMapOtherHeadingsSameTruth) {
  const sim::World world = small_world(10, 7);
  const auto positions = random_imaging_positions(world, 4, 11);
  QrmImagingSettings settings;
  settings.sensor.bearing_noise_deg = 0.05;
  settings.sensor.seed = 5;
  qrm::RelationalMap first;
  qrm::RelationalMap second;
  const auto r1 = qrm_imaging_tour(world, positions, settings, first);
  const auto r2 = qrm_imaging_tour(world, positions, settings, second);
  EXPECT_TRUE(first.same_relations(second));
  for (std::size_t i = 0; i < r1.size(); ++i) {
    EXPECT_EQ(r1[i].heading, r2[i].heading);
    EXPECT_EQ(r1[i].fused.triples, r2[i].fused.triples);
    EXPECT_EQ(r1[i].fused.refined, r2[i].fused.refined);
  }
  // Other zero directions give other bearings but, without noise, a map of the same truth.
  QrmImagingSettings turned;
  turned.heading_seed = 99;
  qrm::RelationalMap third;
  const auto r3 = qrm_imaging_tour(world, positions, turned, third);
  EXPECT_NE(r3.front().heading, r1.front().heading);
  EXPECT_EQ(lost_true_states(third, world), 0);
}

TEST(QrmImaging, RandomPositionsKeepClearAndRepeat) {
  const sim::World world = small_world(30, 3);
  const auto a = random_imaging_positions(world, 50, 4);
  const auto b = random_imaging_positions(world, 50, 4);
  const auto c = random_imaging_positions(world, 50, 5);
  ASSERT_EQ(a.size(), 50U);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (const Eigen::Vector2d& p : a) {
    EXPECT_TRUE(sim::keeps_clear(world, p, 10));
    EXPECT_GE(p.x(), 0);
    EXPECT_LT(p.x(), world.size.x());
    EXPECT_GE(p.y(), 0);
    EXPECT_LT(p.y(), world.size.y());
  }
  // No point of a 20 mm workspace keeps 20 mm from a marble in its middle.
  sim::World full;
  full.size = {20, 20};
  full.objects = {{10, 10}};
  EXPECT_THROW(random_imaging_positions(full, 1, 1, 20), std::invalid_argument);
}

}  // namespace
}  // namespace neopipe::rig
