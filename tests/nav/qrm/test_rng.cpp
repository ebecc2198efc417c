// The RNG (spec qrm.md §8): edge costs and pruning, the true RNG through the EDC against distances,
// the full-knowledge map's estimate, and Dijkstra with its tie rule.

#include <gtest/gtest.h>

#include <random>
#include <utility>
#include <vector>

#include "nav/qrm/rng.hpp"
#include "scenes.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)
using Edges = std::vector<std::pair<std::size_t, std::size_t>>;

// A map that knows every relation exactly.
RelationalMap full_map(const std::vector<Eigen::Vector2d>& p) {
  RelationalMap map;
  for (LandmarkId i = 0; i < p.size(); ++i) map.add_landmark(i);
  for (LandmarkId i = 0; i < p.size(); ++i) {
    for (LandmarkId j = i + 1; j < p.size(); ++j) {
      for (LandmarkId k = j + 1; k < p.size(); ++k) {
        EXPECT_NE(map.fuse(i, j, k, StateSet{classify(p[i], p[j], p[k])}), FuseOutcome::inconsistent);
      }
    }
  }
  return map;
}

Edges edges_of(const RngEstimate& rng) {
  Edges e;
  for (const RngEdge& edge : rng.edges) e.emplace_back(edge.i, edge.j);
  return e;
}

const std::vector<Eigen::Vector2d> kExample{{0, 0}, {4, 0.5}, {1.5, 1.2}, {9, -1}, {6, 4.3}};

}  // namespace

TEST(QrmRng, CostExampleAndPruning) {
  const std::vector<StateSet> others{{5, 7, 13}, {1, 2}};
  EXPECT_DOUBLE_EQ(rng_edge_cost(others, 4).value(), 1.0 / 6);
  EXPECT_FALSE(rng_edge_cost(std::vector<StateSet>{{5, 7, 13}, {8, 14}}, 4).has_value());
  EXPECT_EQ(rng_edge_cost(std::vector<StateSet>{{1, 2}, StateSet::range(15, 20)}, 4).value(), 0.0);
  // Through a map: 01:2 and 01:3 stored as in the example.
  RelationalMap map;
  for (LandmarkId i = 0; i < 4; ++i) map.add_landmark(i);
  ASSERT_NE(map.fuse(0, 1, 2, {5, 7, 13}), FuseOutcome::inconsistent);
  ASSERT_NE(map.fuse(0, 1, 3, {1, 2}), FuseOutcome::inconsistent);
  ASSERT_EQ(map.relation(0, 1, 2), (StateSet{5, 7, 13}));
  ASSERT_EQ(map.relation(0, 1, 3), (StateSet{1, 2}));
  const auto edge = rng_edge(map, 1, 0);
  ASSERT_TRUE(edge.has_value());
  EXPECT_EQ(edge->i, 0U);
  EXPECT_EQ(edge->j, 1U);
  EXPECT_DOUBLE_EQ(edge->cost, 1.0 / 6);
  ASSERT_NE(map.fuse(0, 1, 3, {1}), FuseOutcome::inconsistent);
  ASSERT_NE(map.fuse(0, 1, 2, {7, 13}), FuseOutcome::inconsistent);
  EXPECT_FALSE(rng_edge(map, 0, 1).has_value());  // 01:2 wholly in the lune
}

TEST(QrmRng, NavigationExample) {
  const Edges expected{{0, 2}, {1, 2}, {1, 3}, {1, 4}};
  EXPECT_EQ(true_rng(kExample), expected);
  EXPECT_EQ(rng_by_distances(kExample), expected);
  const RngEstimate rng = estimate_rng(full_map(kExample));
  EXPECT_EQ(edges_of(rng), expected);
  for (const RngEdge& e : rng.edges) EXPECT_EQ(e.cost, 0.0);
  EXPECT_EQ(plan_route(rng, 0, 3), (std::vector<LandmarkId>{0, 2, 1, 3}));
  EXPECT_EQ(plan_route(rng, 3, 0), (std::vector<LandmarkId>{3, 1, 2, 0}));
  EXPECT_EQ(plan_route(rng, 4, 4), (std::vector<LandmarkId>{4}));
  // An empty map knows nothing: every pair is a candidate of equal cost, and the route is direct.
  RelationalMap empty;
  for (LandmarkId i = 0; i < 5; ++i) empty.add_landmark(i);
  EXPECT_EQ(estimate_rng(empty).edges.size(), 10U);
  EXPECT_EQ(plan_route(estimate_rng(empty), 0, 3), (std::vector<LandmarkId>{0, 3}));
}

TEST(QrmRng, DijkstraWeighsCostsAndBreaksTiesLexicographically) {
  RngEstimate rng;
  rng.unit = 100;
  // A square 0-1-3, 0-2-3 of equal weights: 0,1,3 is the smaller sequence.
  rng.edges = {{0, 2, 0, 0}, {2, 3, 0, 0}, {0, 1, 0, 0}, {1, 3, 0, 0}};
  EXPECT_EQ(plan_route(rng, 0, 3), (std::vector<LandmarkId>{0, 1, 3}));
  EXPECT_EQ(plan_route(rng, 3, 0), (std::vector<LandmarkId>{3, 1, 0}));
  // A cost on 1-3 sends the route through 2.
  rng.edges[3].scaled_cost = 1;
  EXPECT_EQ(plan_route(rng, 0, 3), (std::vector<LandmarkId>{0, 2, 3}));
  // Three uncertain hops cost more than two certain ones only when 1 + c adds up so.
  rng.edges = {{0, 1, 0, 0}, {1, 2, 0, 0}, {2, 3, 0, 0}, {0, 4, 0, 40}, {3, 4, 0, 40}};
  EXPECT_EQ(plan_route(rng, 0, 3), (std::vector<LandmarkId>{0, 4, 3}));  // 2 * 140 < 300
  rng.edges[3].scaled_cost = 90;
  EXPECT_EQ(plan_route(rng, 0, 3), (std::vector<LandmarkId>{0, 1, 2, 3}));  // 300 < 190 + 140
  rng.edges.pop_back();
  rng.edges.erase(rng.edges.begin() + 2);
  EXPECT_TRUE(plan_route(rng, 0, 3).empty());  // unreachable
}

TEST(QrmRng, FullKnowledgeEstimateIsTheTrueRngOnRandomWorlds) {
  std::mt19937_64 rng(12);
  for (int world = 0; world < 12; ++world) {
    const std::vector<Eigen::Vector2d> p = scenes::random_landmarks(rng, 8 + world);
    const Edges truth = true_rng(p);
    EXPECT_EQ(truth, rng_by_distances(p));
    const RngEstimate estimate = estimate_rng(full_map(p));
    EXPECT_EQ(edges_of(estimate), truth);
    for (const RngEdge& e : estimate.edges) EXPECT_EQ(e.cost, 0.0);
  }
}

TEST(QrmRng, DegenerateTriplesAreNamed) {
  const std::vector<Eigen::Vector2d> collinear{{0, 0}, {5, 0}, {1, 2.5}, {10, 0}};
  try {
    (void)true_rng(collinear);
    ADD_FAILURE();
  } catch (const DegenerateTripleError& e) {
    EXPECT_EQ(e.i, 0U);
    EXPECT_EQ(e.j, 1U);
    EXPECT_EQ(e.k, 3U);
  }
}
