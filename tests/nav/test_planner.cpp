// The planner against brute force: every simple path of small random graphs (cycles only add
// nonnegative cost, so the optimum is always simple), and a Pareto-front reference without any
// pruning on larger graphs, where the compromise comes from the convex hull of many (D, U) points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "nav/mapmaker/planner.hpp"

namespace neopipe::nav::mapmaker {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double ratio_of(double d, double u) {
  return d == 0 ? 0.0 : d * std::exp(u);
}

// Random graph with D and U positively correlated, as window travel and its unreliability are, plus
// a share of edges where they disagree so the three criteria pick different paths. L, the distance
// between the landmarks, is D give or take the corner changes, in quarters so that L ties and D
// must break them; it comes from a stream of its own so that D and U do not depend on it.
PlanGraph random_graph(std::uint32_t nodes, double density, std::uint64_t seed) {
  std::mt19937_64 rng(seed), landmark_rng(seed ^ 0x5eed);
  std::uniform_real_distribution<double> unit(0, 1);
  PlanGraph g(nodes);
  for (std::uint32_t a = 0; a < nodes; ++a)
    for (std::uint32_t b = 0; b < nodes; ++b) {
      if (a == b || unit(rng) > density) continue;
      const double d = std::round(unit(rng) * 100) / 4;  // quarters of a mm: exact ties happen
      const double u = unit(rng) < 0.7 ? d * 0.004 * unit(rng) : 0.3 * unit(rng);
      const double l = std::max(0.0, d + std::round((unit(landmark_rng) - 0.5) * 40) / 4);
      g.add_edge({a, b, d, u, l});
    }
  return g;
}

struct Best {
  double d = kInf, u = kInf, r = kInf, l = kInf;
};

struct Bests {
  Best by_d, by_u, by_r, by_l;
};

// Every simple path from `source` to `target` by depth-first search; keeps the best key per criterion.
void enumerate(const PlanGraph& g, std::uint32_t v, std::uint32_t target, const Best& cost, std::vector<char>& on_path,
               Bests& best) {
  if (v == target) {
    const auto [d, u, r, l] = cost;
    if (std::tie(d, u) < std::tie(best.by_d.d, best.by_d.u)) best.by_d = cost;
    if (std::tie(u, d) < std::tie(best.by_u.u, best.by_u.d)) best.by_u = cost;
    if (std::tie(r, d, u) < std::tie(best.by_r.r, best.by_r.d, best.by_r.u)) best.by_r = cost;
    if (std::tie(l, d, u) < std::tie(best.by_l.l, best.by_l.d, best.by_l.u)) best.by_l = cost;
    return;
  }
  on_path[v] = 1;
  for (const std::uint32_t e : g.out_edges(v)) {
    const PlanEdge& edge = g.edges()[e];
    if (on_path[edge.to]) continue;
    const double d = cost.d + edge.distance, u = cost.u + edge.unreliability;
    enumerate(g, edge.to, target, {d, u, ratio_of(d, u), cost.l + edge.landmark_distance}, on_path, best);
  }
  on_path[v] = 0;
}

void expect_valid_path(const PlanGraph& g, const PlannedPath& p, std::uint32_t source, std::uint32_t target) {
  ASSERT_FALSE(p.edges.empty());
  EXPECT_EQ(g.edges()[p.edges.front()].from, source);
  EXPECT_EQ(g.edges()[p.edges.back()].to, target);
  double d = 0, u = 0, l = 0;
  for (std::size_t k = 0; k < p.edges.size(); ++k) {
    if (k > 0) {
      EXPECT_EQ(g.edges()[p.edges[k]].from, g.edges()[p.edges[k - 1]].to);
    }
    d += g.edges()[p.edges[k]].distance;
    u += g.edges()[p.edges[k]].unreliability;
    l += g.edges()[p.edges[k]].landmark_distance;
  }
  EXPECT_EQ(p.distance, d);
  EXPECT_EQ(p.unreliability, u);
  EXPECT_EQ(p.landmark_distance, l);
}

TEST(Planner, EachCriterionEqualsBruteForceOverAllSimplePaths) {
  int compared = 0, criteria_differ = 0, landmark_differs = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const PlanGraph g = random_graph(8, 0.35, seed);
    for (std::uint32_t s = 0; s < 8; ++s)
      for (std::uint32_t t = 0; t < 8; ++t) {
        if (s == t) continue;
        Bests best;
        std::vector<char> on_path(8, 0);
        enumerate(g, s, t, {0, 0, 0, 0}, on_path, best);
        const auto [by_d, by_u, by_r, by_l] = best;
        const std::uint32_t src[] = {s}, dst[] = {t};
        const auto pd = plan_path(g, src, dst, CostCriterion::distance);
        const auto pu = plan_path(g, src, dst, CostCriterion::reliability);
        const auto pr = plan_path(g, src, dst, CostCriterion::ratio);
        const auto pl = plan_path(g, src, dst, CostCriterion::landmark);
        ASSERT_EQ(pd.has_value(), by_d.d < kInf) << "seed " << seed << " " << s << "->" << t;
        ASSERT_EQ(pu.has_value(), pd.has_value());
        ASSERT_EQ(pr.has_value(), pd.has_value());
        ASSERT_EQ(pl.has_value(), pd.has_value());
        if (!pd) continue;
        ++compared;
        expect_valid_path(g, *pd, s, t);
        expect_valid_path(g, *pu, s, t);
        expect_valid_path(g, *pr, s, t);
        expect_valid_path(g, *pl, s, t);
        // Sums along different paths may round differently, hence the tolerance on equal keys.
        EXPECT_NEAR(pd->distance, by_d.d, 1e-9) << "seed " << seed << " " << s << "->" << t;
        EXPECT_NEAR(pd->unreliability, by_d.u, 1e-9);
        EXPECT_NEAR(pu->unreliability, by_u.u, 1e-9) << "seed " << seed << " " << s << "->" << t;
        EXPECT_NEAR(pu->distance, by_u.d, 1e-9);
        EXPECT_NEAR(pr->ratio(), by_r.r, 1e-9 * by_r.r) << "seed " << seed << " " << s << "->" << t;
        EXPECT_NEAR(pl->landmark_distance, by_l.l, 1e-9) << "seed " << seed << " " << s << "->" << t;
        EXPECT_NEAR(pl->distance, by_l.d, 1e-9) << "seed " << seed << " " << s << "->" << t;
        EXPECT_NEAR(pl->unreliability, by_l.u, 1e-9);
        if (pr->ratio() < std::min(pd->ratio(), pu->ratio()) - 1e-9) ++criteria_differ;
        if (pl->distance > pd->distance + 1e-9) ++landmark_differs;
      }
  }
  EXPECT_GT(compared, 1000);
  // The compromise must sometimes beat both single-criterion paths, or the test would not show that
  // the compromise search is more than picking the better of the two; likewise the landmark-based
  // shortest path must sometimes be longer in D, or min L would not be tested apart from min D.
  EXPECT_GT(criteria_differ, 10);
  EXPECT_GT(landmark_differs, 10);
}

// Every Pareto-optimal (D, U) label at every node, by label correcting without any bound; the
// reference for the compromise search on graphs too large to enumerate.
double reference_min_ratio(const PlanGraph& g, std::uint32_t source, std::uint32_t target, double offset = 0) {
  std::vector<std::vector<std::pair<double, double>>> front(g.node_count());
  std::vector<std::pair<std::uint32_t, std::pair<double, double>>> queue{{source, {0, 0}}};
  front[source].push_back({0, 0});
  while (!queue.empty()) {
    const auto [v, label] = queue.back();
    queue.pop_back();
    if (std::find(front[v].begin(), front[v].end(), label) == front[v].end()) continue;  // since dominated
    for (const std::uint32_t e : g.out_edges(v)) {
      const PlanEdge& edge = g.edges()[e];
      const std::pair<double, double> next{label.first + edge.distance, label.second + edge.unreliability};
      auto& f = front[edge.to];
      if (std::any_of(f.begin(), f.end(),
                      [&](const auto& o) { return o.first <= next.first && o.second <= next.second; }))
        continue;
      std::erase_if(f, [&](const auto& o) { return next.first <= o.first && next.second <= o.second; });
      f.push_back(next);
      queue.push_back({edge.to, next});
    }
  }
  double best = kInf;
  for (const auto& [d, u] : front[target]) best = std::min(best, ratio_of(d + offset, u));
  return best;
}

TEST(Planner, RatioEqualsTheUnprunedParetoFrontOnLargerGraphs) {
  for (const double offset : {0.0, 50.0}) {  // the paper's D / R, and with a look's worth of travel
    for (std::uint64_t seed = 100; seed < 106; ++seed) {
      PlanGraph g = random_graph(120, 0.04, seed);
      g.set_ratio_offset(offset);
      for (std::uint32_t t = 1; t < 120; t += 7) {
        const double expected = reference_min_ratio(g, 0, t, offset);
        const std::uint32_t src[] = {0}, dst[] = {t};
        const auto path = plan_path(g, src, dst, CostCriterion::ratio);
        ASSERT_EQ(path.has_value(), expected < kInf) << "seed " << seed << " target " << t;
        if (path) {
          const double found = ratio_of(path->distance + offset, path->unreliability);
          EXPECT_NEAR(found, expected, 1e-9 * expected) << "offset " << offset << " seed " << seed << " target " << t;
        }
      }
    }
  }
}

TEST(Planner, RatioFindsTheBestOfAHugeParetoFrontWithFewSearches) {
  // A ladder of 14 stages, each crossed by a short risky or a long safe edge: up to 2^14 Pareto
  // points at the end, of which the convex hull keeps a few.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    constexpr std::uint32_t kStages = 14;
    PlanGraph g(kStages + 1);
    for (std::uint32_t k = 0; k < kStages; ++k) {
      const double d = 10 + 40 * unit(rng);
      const double u = 0.05 + 0.3 * unit(rng);
      g.add_edge({k, k + 1, d, u});
      g.add_edge({k, k + 1, d * (1.5 + unit(rng)), u * 0.2 * unit(rng)});
    }
    const std::uint32_t src[] = {0}, dst[] = {kStages};
    PlanStats stats;
    const auto path = plan_path(g, src, dst, CostCriterion::ratio, stats);
    ASSERT_TRUE(path.has_value());
    const double expected = reference_min_ratio(g, 0, kStages);
    EXPECT_NEAR(path->ratio(), expected, 1e-9 * expected) << "seed " << seed;
    EXPECT_LE(stats.searches, 2U + 2 * kStages) << "seed " << seed;
  }
}

TEST(Planner, UnreachableTargetIsNulloptAndCostsLittle) {
  // Two halves with edges only from the second to the first: nothing in the second half is
  // reachable from node 0. The search must not wander the first half's Pareto fronts.
  const std::uint32_t half = 500;
  PlanGraph g(2 * half);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (std::uint32_t a = 0; a < 2 * half; ++a)
    for (int k = 0; k < 6; ++k) {
      const auto b = static_cast<std::uint32_t>(rng() % half);
      if (a != b) g.add_edge({a, b, unit(rng) * 10, unit(rng)});
    }
  const std::uint32_t src[] = {0}, dst[] = {half + 3};
  for (const CostCriterion c : kCriteria) {
    PlanStats stats;
    EXPECT_FALSE(plan_path(g, src, dst, c, stats).has_value());
    EXPECT_LE(stats.labels_created, g.edges().size() + 1) << criterion_name(c);
  }
}

TEST(Planner, SourceThatIsATargetGivesTheEmptyPath) {
  PlanGraph g(3);
  g.add_edge({0, 1, 1, 0.1});
  const std::uint32_t src[] = {0, 1}, dst[] = {1};
  for (const CostCriterion c : kCriteria) {
    const auto p = plan_path(g, src, dst, c);
    ASSERT_TRUE(p.has_value());
    EXPECT_TRUE(p->edges.empty());
    EXPECT_EQ(p->ratio(), 0);
  }
}

TEST(Planner, TiesGoToTheEarlierEdgeAndTheSmallerNode) {
  // Two parallel equal edges 0 -> 1, and two equal routes to 3 through 1 and through 2.
  PlanGraph g(4);
  g.add_edge({0, 1, 5, 0.5});  // 0
  g.add_edge({0, 1, 5, 0.5});  // 1
  g.add_edge({0, 2, 5, 0.5});  // 2
  g.add_edge({2, 3, 5, 0.5});  // 3
  g.add_edge({1, 3, 5, 0.5});  // 4
  const std::uint32_t src[] = {0}, dst[] = {3};
  for (const CostCriterion c : kCriteria) {
    const auto p = plan_path(g, src, dst, c);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->edges, (std::vector<std::uint32_t>{0, 4})) << criterion_name(c);
  }
}

TEST(Planner, LandmarkTiesGoToTheShorterThenTheMoreReliable) {
  // The four corners a landmark can be held at give parallel edges of equal L: D must choose, then U.
  PlanGraph g(3);
  g.add_edge({0, 1, 3, 0.1, 5});   // 0
  g.add_edge({0, 1, 2, 0.3, 5});   // 1
  g.add_edge({0, 1, 2, 0.2, 5});   // 2: least D, then least U
  g.add_edge({0, 1, 9, 0.2, 5});   // 3
  g.add_edge({1, 2, 1, 0.0, 5});   // 4
  g.add_edge({0, 2, 1, 0.0, 11});  // 5: far less D, but more L
  const std::uint32_t src[] = {0}, dst[] = {2};
  const auto p = plan_path(g, src, dst, CostCriterion::landmark);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->edges, (std::vector<std::uint32_t>{2, 4}));
  EXPECT_EQ(p->landmark_distance, 10);
  EXPECT_EQ(p->distance, 3);
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::distance)->edges, std::vector<std::uint32_t>{5});
}

TEST(Planner, TiesOfTheFirstCriterionAreSearchedInOrderOfTheSecond) {
  // 0 reaches 1 and 2 at the same first cost; 1 (the smaller id) is cheaper through 2, by an edge
  // that adds nothing to the first criterion. Node 2 must be settled before 1, as its key is smaller
  // on the second criterion: a search ordered by the first criterion and the node id alone settles 1
  // too early, through the direct edge (tests/mutation/mutants.json, N02).
  const auto edge = [](std::uint32_t a, std::uint32_t b, CostCriterion c, double first, double second) {
    switch (c) {
      case CostCriterion::reliability:
        return PlanEdge{a, b, second, first, 0};
      case CostCriterion::landmark:
        return PlanEdge{a, b, second, 0, first};
      default:
        return PlanEdge{a, b, first, second, 0};
    }
  };
  for (const CostCriterion c : {CostCriterion::distance, CostCriterion::reliability, CostCriterion::landmark}) {
    PlanGraph g(4);
    g.add_edge(edge(0, 1, c, 1, 5));  // 0
    g.add_edge(edge(0, 2, c, 1, 0));  // 1
    g.add_edge(edge(2, 1, c, 0, 0));  // 2
    g.add_edge(edge(1, 3, c, 1, 0));  // 3
    const std::uint32_t src[] = {0}, dst[] = {3};
    const auto p = plan_path(g, src, dst, c);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->edges, (std::vector<std::uint32_t>{1, 2, 3})) << criterion_name(c);
  }
}

TEST(Planner, RatioTiesGoToTheShorter) {
  // D e^U is exactly 1 on both routes: 1 e^0 and 0.5 e^(log 2). The compromise keeps the shorter
  // (tests/mutation/mutants.json, N10).
  const double u = std::log(2.0);
  ASSERT_EQ(0.5 * std::exp(u), 1.0) << "this libm's exp(log 2) is not exactly 2: the tie is not exact";
  PlanGraph g(3);
  g.add_edge({0, 1, 1, 0});    // 0: the safe route
  g.add_edge({0, 2, 0.5, u});  // 1: the short route
  g.add_edge({1, 2, 0, 0});    // 2
  const std::uint32_t src[] = {0}, dst[] = {2};
  const auto p = plan_path(g, src, dst, CostCriterion::ratio);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->edges, std::vector<std::uint32_t>{1});
  EXPECT_EQ(p->ratio(), 1.0);
}

TEST(Planner, ZeroCostCyclesEnd) {
  PlanGraph g(4);
  g.add_edge({0, 1, 0, 0});
  g.add_edge({1, 2, 0, 0});
  g.add_edge({2, 0, 0, 0});
  g.add_edge({2, 3, 1, 0});
  const std::uint32_t src[] = {0}, dst[] = {3};
  for (const CostCriterion c : kCriteria) {
    const auto p = plan_path(g, src, dst, c);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->edges, (std::vector<std::uint32_t>{0, 1, 3})) << criterion_name(c);
  }
}

TEST(Planner, TheCompromiseLiesBetweenTheExtremes) {
  // A short risky edge, a long safe detour, and a middle way that is best under D/R.
  PlanGraph g(4);
  g.add_edge({0, 3, 100, 1.0});  // shortest: D/R = 271.8
  g.add_edge({0, 1, 150, 0.0});  // most reliable: D 300, U 0, D/R 300
  g.add_edge({1, 3, 150, 0.0});
  g.add_edge({0, 2, 60, 0.1});  // compromise: D 120, U 0.4, D/R 179.0
  g.add_edge({2, 3, 60, 0.3});
  const std::uint32_t src[] = {0}, dst[] = {3};
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::distance)->edges, std::vector<std::uint32_t>{0});
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::reliability)->edges, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::ratio)->edges, (std::vector<std::uint32_t>{3, 4}));
}

TEST(Planner, WithARatioOffsetAGoalInViewIsNotFreeWhateverItsUnreliability) {
  // 0 -> 1 with D = 0 (the goal in view) but U = 3 (R 0.05); 0 -> 2 -> 1, 60 mm, certain. D / R
  // alone takes the first: 0 * e^3 = 0. Counting a look as a window's travel, (0 + 50) e^3 = 1004
  // against (60 + 50) e^0 = 110: the certain route.
  PlanGraph g(3);
  g.add_edge({0, 1, 0, 3.0});
  g.add_edge({0, 2, 30, 0.0});
  g.add_edge({2, 1, 30, 0.0});
  const std::uint32_t src[] = {0}, dst[] = {1};
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::ratio)->edges, std::vector<std::uint32_t>{0});
  g.set_ratio_offset(50);
  EXPECT_EQ(plan_path(g, src, dst, CostCriterion::ratio)->edges, (std::vector<std::uint32_t>{1, 2}));
  // A small U still wins when its route is much shorter: (0 + 50) e^0.5 = 82 < 110.
  PlanGraph h(3);
  h.add_edge({0, 1, 0, 0.5});
  h.add_edge({0, 2, 30, 0.0});
  h.add_edge({2, 1, 30, 0.0});
  h.set_ratio_offset(50);
  EXPECT_EQ(plan_path(h, src, dst, CostCriterion::ratio)->edges, std::vector<std::uint32_t>{0});
  EXPECT_THROW(h.set_ratio_offset(-1), std::invalid_argument);
  EXPECT_THROW(h.set_ratio_offset(std::nan("")), std::invalid_argument);
}

TEST(Planner, RejectsBadEdgesAndNodes) {
  PlanGraph g(2);
  EXPECT_THROW(g.add_edge({0, 2, 1, 0}), std::invalid_argument);
  EXPECT_THROW(g.add_edge({0, 1, -1, 0}), std::invalid_argument);
  EXPECT_THROW(g.add_edge({0, 1, 1, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(g.add_edge({0, 1, kInf, 0}), std::invalid_argument);
  const std::uint32_t bad[] = {5}, ok[] = {1};
  EXPECT_THROW(plan_path(g, bad, ok, CostCriterion::distance), std::invalid_argument);
  EXPECT_THROW(plan_path(g, ok, bad, CostCriterion::ratio), std::invalid_argument);
  EXPECT_THROW(g.add_edge({0, 1, 1, 0, -1}), std::invalid_argument);
  for (const CostCriterion c : kCriteria) EXPECT_EQ(parse_criterion(criterion_name(c)), c);
  EXPECT_EQ(parse_criterion("landmark"), CostCriterion::landmark);
  EXPECT_FALSE(parse_criterion("Ratio").has_value());
  EXPECT_FALSE(parse_criterion("landmarks").has_value());
}

// The out-edge index is built lazily, by the first query after an add_edge. A graph planned on while
// it grows must, once complete, plan exactly as the same edges added in one go (the same paths, ties
// included), and planning on it again (the index reused) must change nothing. (Two graphs built
// alike and planned alike, which this test replaces, cannot tell a stale index from a fresh one.)
TEST(Planner, AGraphPlannedOnWhileItGrowsPlansAsOneBuiltInOneGo) {
  const PlanGraph whole = random_graph(60, 0.08, 42);
  const std::vector<PlanEdge>& edges = whole.edges();
  const std::uint32_t src[] = {0, 1}, dst[] = {50, 59};
  PlanGraph grown(60);
  std::vector<std::optional<PlannedPath>> before;  // on the first two thirds of the edges
  for (std::size_t k = 0; k < edges.size(); ++k) {
    grown.add_edge(edges[k]);
    if (k + 1 == edges.size() / 3) {
      for (const CostCriterion c : kCriteria) (void)plan_path(grown, src, dst, c);
    }
    if (k + 1 == 2 * edges.size() / 3) {
      for (const CostCriterion c : kCriteria) before.push_back(plan_path(grown, src, dst, c));
    }
  }
  int changed = 0;  // criteria whose best path the last third of the edges changes
  for (std::size_t i = 0; i < kCriteria.size(); ++i) {
    const CostCriterion c = kCriteria[i];
    SCOPED_TRACE(criterion_name(c));
    const auto want = plan_path(whole, src, dst, c);
    ASSERT_TRUE(want.has_value());
    for (int round = 0; round < 2; ++round) {  // the first query indexes the grown graph, the second reuses it
      const auto got = plan_path(grown, src, dst, c);
      ASSERT_TRUE(got.has_value()) << "round " << round;
      EXPECT_EQ(got->edges, want->edges) << "round " << round;
      EXPECT_EQ(got->distance, want->distance) << "round " << round;
      EXPECT_EQ(got->unreliability, want->unreliability) << "round " << round;
    }
    if (!before[i] || before[i]->edges != want->edges) ++changed;
  }
  EXPECT_GT(changed, 0) << "the last edges change no path: the test would not see them missing";
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
