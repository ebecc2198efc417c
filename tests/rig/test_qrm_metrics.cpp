// The metrics of QRM map building (rig/qrm_metrics.hpp, spec qrm.md §10) on hand-made maps.

#include <gtest/gtest.h>

#include "nav/qrm/edc.hpp"
#include "rig/qrm_metrics.hpp"

namespace neopipe::rig {
namespace {

namespace qrm = nav::qrm;

// Spec §8's example: RNG = {0-2, 1-2, 1-3, 1-4}.
const std::vector<Eigen::Vector2d> kPoints{{0, 0}, {4, 0.5}, {1.5, 1.2}, {9, -1}, {6, 4.3}};

qrm::RelationalMap empty_map(std::size_t n) {
  qrm::RelationalMap map;
  for (std::size_t i = 0; i < n; ++i) map.add_landmark(static_cast<qrm::LandmarkId>(i));
  return map;
}

// Every relation told its true state.
qrm::RelationalMap full_map(const std::vector<Eigen::Vector2d>& p) {
  qrm::RelationalMap map = empty_map(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = 0; j < p.size(); ++j) {
      for (std::size_t k = 0; k < p.size(); ++k) {
        if (i == j || j == k || i == k) continue;
        const auto outcome = map.fuse(static_cast<qrm::LandmarkId>(i), static_cast<qrm::LandmarkId>(j),
                                      static_cast<qrm::LandmarkId>(k), {qrm::classify(p[i], p[j], p[k])});
        EXPECT_NE(outcome, qrm::FuseOutcome::inconsistent);
      }
    }
  }
  return map;
}

TEST(QrmMetrics, FullKnowledge) {
  const QrmMetrics m = qrm_metrics(full_map(kPoints), kPoints);
  EXPECT_EQ(m.landmarks, 5U);
  EXPECT_EQ(m.triples, 10U);
  EXPECT_DOUBLE_EQ(m.m1, 100);
  EXPECT_DOUBLE_EQ(m.m2, 100);
  EXPECT_DOUBLE_EQ(m.m3, 0);
  EXPECT_DOUBLE_EQ(m.m4, 0);
  EXPECT_EQ(m.open_wrong, 0U);
  EXPECT_EQ(m.lost, 0U);
  const RngEdges truth{{0, 2}, {1, 2}, {1, 3}, {1, 4}};
  EXPECT_EQ(m.rng, truth);
  EXPECT_EQ(m.certain_rng, truth);
  EXPECT_TRUE(m.versus_truth.equal);
  EXPECT_DOUBLE_EQ(m.versus_truth.precision, 1);
  EXPECT_DOUBLE_EQ(m.versus_truth.recall, 1);
}

TEST(QrmMetrics, EmptyMap) {
  const QrmMetrics m = qrm_metrics(empty_map(kPoints.size()), kPoints);
  EXPECT_DOUBLE_EQ(m.m1, 0);
  EXPECT_DOUBLE_EQ(m.m2, 0);
  EXPECT_EQ(m.open_wrong, 19U * 30U);
  // Every pair is a candidate of cost 3 * (4/20) / 5.
  EXPECT_EQ(m.rng.size(), 10U);
  EXPECT_NEAR(m.m3, 10 * 3 * 0.2 / 5, 1e-12);
  EXPECT_TRUE(m.certain_rng.empty());
  EXPECT_DOUBLE_EQ(m.versus_truth.recall, 1);
  EXPECT_DOUBLE_EQ(m.versus_truth.precision, 0.4);
  // M4: per relation, the 19 - |adjacent(truth)| far states of its 19 wrong ones.
  double far = 0;
  for (std::size_t i = 0; i < 5; ++i) {
    for (std::size_t j = 0; j < 5; ++j) {
      for (std::size_t k = 0; k < 5; ++k) {
        if (i == j || j == k || i == k || !(i < j && j < k)) continue;
        for (const auto& [p, q, r] : std::array<std::array<std::size_t, 3>, 3>{{{i, j, k}, {j, k, i}, {k, i, j}}}) {
          far += 19 - qrm::adjacent(qrm::classify(kPoints[p], kPoints[q], kPoints[r])).count();
        }
      }
    }
  }
  EXPECT_NEAR(m.m4, 100 * far / (19 * 30), 1e-9);
  // A map that has not met the landmarks at all counts the same.
  const QrmMetrics none = qrm_metrics(qrm::RelationalMap{}, kPoints);
  EXPECT_DOUBLE_EQ(none.m1, 0);
  EXPECT_EQ(none.open_wrong, m.open_wrong);
  EXPECT_TRUE(none.rng.empty());
  EXPECT_DOUBLE_EQ(none.versus_truth.recall, 0);
}

TEST(QrmMetrics, OneRelationKnown) {
  qrm::RelationalMap map = empty_map(3);
  const std::vector<Eigen::Vector2d> p{kPoints[0], kPoints[1], kPoints[2]};
  const qrm::State truth = qrm::classify(p[0], p[1], p[2]);
  // ij:k told to be {truth, one wrong state not adjacent}: propagation refines jk:i and ki:j too.
  qrm::StateSet told{truth};
  qrm::State far = 0;
  for (qrm::State s = 1; s <= 20 && far == 0; ++s) {
    if (s != truth && !qrm::adjacent(truth).contains(s)) far = s;
  }
  told.insert(far);
  map.fuse(0, 1, 2, told);
  const QrmMetrics m = qrm_metrics(map, p);
  double removed = 0;
  for (const auto& [a, b, c] : std::array<std::array<qrm::LandmarkId, 3>, 3>{{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}}) {
    removed += 20 - map.relation(a, b, c).count();
  }
  EXPECT_NEAR(m.m1, 100 * removed / 57, 1e-12);
  EXPECT_GT(m.m1, 100.0 * 18 / 57);
  EXPECT_DOUBLE_EQ(m.m2, 0);
  EXPECT_GT(m.m4, 0);
  EXPECT_EQ(m.lost, 0U);
  // A map told a wrong state loses the truth, and the metric says so.
  qrm::RelationalMap wrong = empty_map(3);
  wrong.fuse(0, 1, 2, {far});
  EXPECT_EQ(qrm_metrics(wrong, p).lost, 3U);
}

TEST(QrmMetrics, RngComparison) {
  const RngComparison c = compare_rng({{0, 1}, {1, 2}, {2, 3}}, {{1, 2}, {0, 1}});
  EXPECT_EQ(c.estimated, 3U);
  EXPECT_EQ(c.truth, 2U);
  EXPECT_EQ(c.common, 2U);
  EXPECT_NEAR(c.precision, 2.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(c.recall, 1);
  EXPECT_FALSE(c.equal);
  EXPECT_TRUE(compare_rng({{1, 2}, {0, 1}}, {{0, 1}, {1, 2}}).equal);
}

TEST(QrmMetrics, DegenerateTriples) {
  const std::vector<Eigen::Vector2d> line{{0, 0}, {0.7, 3}, {2, 0}, {4, 0}};
  const auto d = qrm::first_degenerate_triple(line);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(*d, (std::array<std::size_t, 3>{0, 2, 3}));
  EXPECT_FALSE(qrm::first_degenerate_triple(kPoints).has_value());
  EXPECT_THROW(qrm_metrics(empty_map(4), line), qrm::DegenerateTripleError);
  sim::WorldRequest request;
  request.objects = 20;
  request.seed = 4;
  const sim::World w = generate_qrm_world(request);
  EXPECT_EQ(w.objects.size(), 20U);
  EXPECT_FALSE(qrm::first_degenerate_triple(w.objects).has_value());
}

}  // namespace
}  // namespace neopipe::rig
