// The map (spec qrm.md §7): the golden example, no true state ever lost, independence of the order
// of measurements, rollback of an inconsistent measurement.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "nav/qrm/operators.hpp"
#include "nav/qrm/relational_map.hpp"
#include "scenes.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

constexpr LandmarkId A = 0;
constexpr LandmarkId B = 1;
constexpr LandmarkId C = 2;
constexpr LandmarkId D = 3;

RelationalMap golden_map() {
  RelationalMap map;
  for (const LandmarkId id : {A, B, C, D}) map.add_landmark(id);
  EXPECT_EQ(map.fuse(C, A, B, {6, 7}), FuseOutcome::refined);
  EXPECT_EQ(map.fuse(C, B, D, {5}), FuseOutcome::refined);
  return map;
}

struct Measurement {
  LandmarkId a, b, c;
  StateSet states;
};

// Measurements of every triple of the `k` nearest landmarks from `images` random camera positions,
// each of all 20 candidates (so the list does not depend on the map it will be fused into).
std::vector<Measurement> measurements(std::mt19937_64& rng, const std::vector<Eigen::Vector2d>& p, int images, int k) {
  std::uniform_real_distribution<double> u(0, 100);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  std::vector<Measurement> out;
  for (int image = 0; image < images; ++image) {
    const Eigen::Vector2d camera{u(rng), u(rng)};
    std::vector<LandmarkId> order(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) order[i] = static_cast<LandmarkId>(i);
    std::sort(order.begin(), order.end(),
              [&](LandmarkId x, LandmarkId y) { return (p[x] - camera).norm() < (p[y] - camera).norm(); });
    order.resize(std::min<std::size_t>(k, order.size()));
    std::sort(order.begin(), order.end());
    const double zero = turn(rng);
    for (std::size_t x = 0; x < order.size(); ++x) {
      for (std::size_t y = x + 1; y < order.size(); ++y) {
        for (std::size_t z = y + 1; z < order.size(); ++z) {
          const LandmarkId i = order[x];
          const LandmarkId j = order[y];
          const LandmarkId l = order[z];
          out.push_back({i, j, l, measure(scenes::sightings(camera, zero, p[i], p[j], p[l]), StateSet::all())});
        }
      }
    }
  }
  return out;
}

}  // namespace

TEST(QrmMap, GoldenExampleOfSection7) {
  const RelationalMap map = golden_map();
  const struct {
    LandmarkId p, q, r;
    StateSet s;
  } expected[] = {{A, B, C, {1, 5, 11}},
                  {B, C, A, {12, 13, 17}},
                  {C, A, B, {6, 7}},
                  {A, B, D, {1, 2}},
                  {B, D, A, {17, 18}},
                  {D, A, B, {7, 8}},
                  {B, C, D, {16}},
                  {C, D, B, {14}},
                  {D, B, C, {9}},
                  {A, C, D, {2, 4, 8, 9, 10, 14, 15, 16}},
                  {C, D, A, {8, 9, 10, 14, 15, 16, 18, 20}},
                  {D, A, C, {8, 9, 10, 14, 15, 16}}};
  for (const auto& e : expected) {
    EXPECT_EQ(map.relation(e.p, e.q, e.r), e.s) << e.p << e.q << ":" << e.r;
    EXPECT_EQ(map.relation(e.q, e.p, e.r), inverse(e.s)) << "read through I";
  }
  const std::vector<Eigen::Vector2d> truth{{0, 0}, {1, -1}, {6, -1}, {2, -6}};
  EXPECT_EQ(scenes::first_lost_truth(map, truth), "");
  EXPECT_EQ(map.inconsistencies(), 0);
}

TEST(QrmMap, NewLandmarksAreRelatedByEverything) {
  RelationalMap map = golden_map();
  map.add_landmark(17);
  EXPECT_TRUE(map.relation(A, B, 17).is_all());
  EXPECT_TRUE(map.relation(17, C, D).is_all());
  EXPECT_EQ(map.relation(A, B, C), (StateSet{1, 5, 11}));  // untouched
  EXPECT_THROW(map.add_landmark(17), std::invalid_argument);
  EXPECT_THROW((void)map.relation(A, B, 99), std::invalid_argument);
  EXPECT_THROW((void)map.relation(A, A, B), std::invalid_argument);
  // Growing past the first block of storage keeps every relation.
  for (LandmarkId id = 100; id < 120; ++id) map.add_landmark(id);
  EXPECT_EQ(map.relation(D, B, C), StateSet{9});
  EXPECT_EQ(map.relation(C, D, A), (StateSet{8, 9, 10, 14, 15, 16, 18, 20}));
  EXPECT_EQ(map.size(), 25U);
}

TEST(QrmMap, NoTrueStateIsEverLostOverRandomWorlds) {
  std::mt19937_64 rng(77);
  int fused = 0;
  for (int world = 0; world < 6; ++world) {
    const std::vector<Eigen::Vector2d> p = scenes::random_landmarks(rng, 9);
    RelationalMap map;
    for (LandmarkId i = 0; i < p.size(); ++i) map.add_landmark(i);
    for (const Measurement& m : measurements(rng, p, 6, 7)) {
      ASSERT_NE(map.fuse(m.a, m.b, m.c, m.states), FuseOutcome::inconsistent);
      ++fused;
    }
    EXPECT_EQ(scenes::first_lost_truth(map, p), "");
    EXPECT_EQ(map.inconsistencies(), 0);
  }
  EXPECT_GT(fused, 1000);
}

TEST(QrmMap, ShuffledMeasurementsGiveTheSameMap) {
  std::mt19937_64 rng(8);
  for (int world = 0; world < 3; ++world) {
    const std::vector<Eigen::Vector2d> p = scenes::random_landmarks(rng, 8);
    std::vector<Measurement> list = measurements(rng, p, 3, 6);
    const auto build = [&](const std::vector<Measurement>& ms, bool reversed_ids) {
      RelationalMap map;
      for (std::size_t n = 0; n < p.size(); ++n) {
        map.add_landmark(static_cast<LandmarkId>(reversed_ids ? p.size() - 1 - n : n));
      }
      for (const Measurement& m : ms) EXPECT_NE(map.fuse(m.a, m.b, m.c, m.states), FuseOutcome::inconsistent);
      return map;
    };
    const RelationalMap first = build(list, false);
    for (int shuffle = 0; shuffle < 4; ++shuffle) {
      std::shuffle(list.begin(), list.end(), rng);
      EXPECT_TRUE(first.same_relations(build(list, shuffle % 2 == 1))) << "world " << world << " shuffle " << shuffle;
    }
    // The same measurement again, or one the map implies, changes nothing.
    RelationalMap again = first;
    EXPECT_EQ(again.fuse(list[0].a, list[0].b, list[0].c, list[0].states), FuseOutcome::unchanged);
    EXPECT_TRUE(again.same_relations(first));
  }
}

TEST(QrmMap, AnInconsistentMeasurementIsRolledBackWholeAndCounted) {
  const RelationalMap before = golden_map();
  // A state outside the stored relation fails at once.
  RelationalMap map = before;
  EXPECT_EQ(map.fuse(A, B, C, {2}), FuseOutcome::inconsistent);
  EXPECT_TRUE(map.same_relations(before));
  EXPECT_EQ(map.inconsistencies(), 1);
  // A measurement that contradicts the map only after propagation: the measured relation was
  // open, so it was stored before the contradiction appeared, and everything is undone. With the
  // real table and states still open, path consistency rarely leaves such a contradiction to find,
  // so a deliberately wrong table (every composition is {1}) makes one.
  CompositionEntries wrong{};
  for (auto& row : wrong) row.fill(StateSet{1});
  const CompositionTable wrong_table(wrong);
  RelationalMap contrived(wrong_table);
  for (const LandmarkId id : {A, B, C, D}) contrived.add_landmark(id);
  ASSERT_EQ(contrived.fuse(A, B, C, {1}), FuseOutcome::refined);
  const RelationalMap consistent = contrived;
  ASSERT_TRUE(contrived.relation(B, C, D).is_all());
  int late = 0;
  for (State s = 1; s <= kStateCount; ++s) {
    RelationalMap trial = consistent;
    if (trial.fuse(B, C, D, StateSet{s}) != FuseOutcome::inconsistent) continue;
    ++late;
    EXPECT_TRUE(trial.same_relations(consistent)) << "BC:D = " << s;
    EXPECT_TRUE(trial.relation(B, C, D).is_all());
    EXPECT_EQ(trial.inconsistencies(), 1);
  }
  EXPECT_GT(late, 0);
}
