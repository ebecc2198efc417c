// One image fused into the map (nav/qrm/observation.hpp): the k nearest, every triple, no true state lost.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/observation.hpp"
#include "scenes.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

// Every landmark of `points` as seen from `camera` with its zero direction at `zero`.
std::vector<LandmarkSighting> panorama(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& camera,
                                       double zero) {
  std::vector<LandmarkSighting> s;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d v = points[i] - camera;
    s.push_back({static_cast<LandmarkId>(i), std::atan2(v.y(), v.x()) - zero, v.norm()});
  }
  return s;
}

}  // namespace

TEST(QrmObservation, FusesEveryTripleOfTheNearestAndKeepsTheTruth) {
  std::mt19937_64 rng(11);
  const auto points = scenes::random_landmarks(rng, 12);
  std::uniform_real_distribution<double> u(0, 100);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  RelationalMap map;
  ObservationOptions options;
  options.nearest = 8;
  std::size_t refined = 0;
  for (int image = 0; image < 5; ++image) {
    const Eigen::Vector2d camera(u(rng), u(rng));
    const auto seen = panorama(points, camera, turn(rng));
    const ObservationReport r = observe(map, seen, options);
    EXPECT_EQ(r.landmarks, 8U);
    EXPECT_EQ(r.triples, 56U);  // C(8, 3)
    EXPECT_EQ(r.inconsistent, 0U);
    refined += r.refined;
    EXPECT_EQ(scenes::first_lost_truth(map, points), "");
  }
  EXPECT_GT(refined, 0U);
  // The first image alone already pins many relations: exact bearings leave few states open.
  std::size_t open = 0;
  std::size_t relations = 0;
  for (const LandmarkId p : map.landmarks()) {
    for (const LandmarkId q : map.landmarks()) {
      for (const LandmarkId r : map.landmarks()) {
        if (p < q && q < r) {
          open += map.relation(p, q, r).count();
          ++relations;
        }
      }
    }
  }
  EXPECT_LT(static_cast<double>(open) / static_cast<double>(relations), 10.0);
}

TEST(QrmObservation, TakesTheKNearestByRangeEstimate) {
  std::mt19937_64 rng(5);
  const auto points = scenes::random_landmarks(rng, 10);
  const Eigen::Vector2d camera(50, 50);
  auto seen = panorama(points, camera, 0.3);
  RelationalMap map;
  ObservationOptions options;
  options.nearest = 4;
  const ObservationReport r = observe(map, seen, options);
  EXPECT_EQ(r.added, 4U);
  EXPECT_EQ(r.triples, 4U);
  std::sort(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.range < b.range; });
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(map.has_landmark(seen[i].id), i < 4) << seen[i].id;
}

TEST(QrmObservation, TheOrderOfSightingsDoesNotMatter) {
  std::mt19937_64 rng(8);
  const auto points = scenes::random_landmarks(rng, 9);
  auto seen = panorama(points, {30, 60}, 1.0);
  RelationalMap in_order;
  observe(in_order, seen);
  std::shuffle(seen.begin(), seen.end(), rng);
  RelationalMap shuffled;
  observe(shuffled, seen);
  EXPECT_TRUE(in_order.same_relations(shuffled));
}

TEST(QrmObservation, RejectsATwiceSeenLandmarkAndBadRanges) {
  RelationalMap map;
  const std::vector<LandmarkSighting> twice{{1, 0.1, 5}, {2, 1.0, 6}, {1, 2.0, 7}};
  EXPECT_THROW(observe(map, twice), std::invalid_argument);
  const std::vector<LandmarkSighting> bad{{1, 0.1, 5}, {2, 1.0, 0}, {3, 2.0, 7}};
  EXPECT_THROW(observe(map, bad), std::invalid_argument);
  const std::vector<LandmarkSighting> nan{{1, std::nan(""), 5}, {2, 1.0, 6}, {3, 2.0, 7}};
  EXPECT_THROW(observe(map, nan), std::invalid_argument);
}
