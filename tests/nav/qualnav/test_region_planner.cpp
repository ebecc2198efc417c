// The orientation-region planner (spec qualnav.md §7) on small hand-made graphs: joins of the two
// ends, the heading rule and its ties, the breadth-first fallback; and the shortcut test on real
// views of a few landmarks.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <vector>

#include "nav/qualnav/topology/arrangement.hpp"
#include "nav/qualnav/topology/region_planner.hpp"

namespace {
namespace qn = neopipe::nav::qualnav;
using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;
constexpr double kEast = 0;
constexpr double kNorth = kPi / 2;
constexpr double kWest = kPi;
constexpr double kSouth = -kPi / 2;

// A node label as a sign vector over eight pairs of made-up landmarks (its bits).
qn::PairSigns signs_of(int label) {
  qn::PairSigns s;
  for (int bit = 0; bit < 8; ++bit) s[{0, static_cast<qn::LandmarkId>(bit + 1)}] = (label >> bit & 1) != 0 ? 1 : -1;
  return s;
}

struct Step {
  int from;
  int to;
  double heading;
};

// Each step is a viewpath of two viewframes: from, then to with the crossing's compass heading.
struct HandGraph {
  explicit HandGraph(const std::vector<Step>& steps) {
    std::vector<qn::RegionObservation> observations;
    std::vector<std::size_t> breaks;
    for (const Step& s : steps) {
      if (!observations.empty()) breaks.push_back(observations.size());
      observations.push_back({signs_of(s.from), {}, std::nullopt});
      observations.push_back({signs_of(s.to), {}, s.heading});
    }
    graph = std::make_unique<qn::RegionGraph>(observations, breaks);
  }
  [[nodiscard]] std::size_t id(int label) const { return *graph->node_with(signs_of(label)); }
  [[nodiscard]] std::vector<int> labels(const std::vector<std::size_t>& nodes) const {
    std::vector<int> out;
    for (const std::size_t n : nodes) {
      for (int label = 0; label < 256; ++label) {
        if (graph->node_with(signs_of(label)) == n) out.push_back(label);
      }
    }
    return out;
  }
  std::unique_ptr<qn::RegionGraph> graph;
};

double bearing_to(const Vector2d& from, const Vector2d& to) {
  return std::atan2(to.y() - from.y(), to.x() - from.x());
}

std::vector<qn::Sighting> panorama(const std::vector<Vector2d>& landmarks, const Vector2d& at) {
  std::vector<qn::Sighting> seen;
  for (qn::LandmarkId i = 0; i < landmarks.size(); ++i) seen.push_back({i, bearing_to(at, landmarks[i])});
  return seen;
}

}  // namespace

TEST(QualnavRegionPlanner, NodesAreDistinctSignVectorsAndEdgesComeFromConsecutiveViews) {
  // One viewpath 1 2 2 3 1: three nodes, edges 1-2, 2-3, 3-1, headings both ways.
  std::vector<qn::RegionObservation> obs;
  for (const auto& [label, heading] :
       std::vector<std::pair<int, double>>{{1, 0}, {2, kEast}, {2, kEast}, {3, kNorth}, {1, kWest}}) {
    obs.push_back({signs_of(label), {}, heading});
  }
  const qn::RegionGraph g(obs);
  ASSERT_EQ(g.nodes().size(), 3U);
  EXPECT_EQ(std::vector<std::size_t>(g.node_of_observation().begin(), g.node_of_observation().end()),
            (std::vector<std::size_t>{0, 1, 1, 2, 0}));
  EXPECT_TRUE(g.adjacent(0, 1) && g.adjacent(1, 2) && g.adjacent(2, 0));
  EXPECT_NEAR(*g.heading(1, 2), kNorth, 1e-12);
  EXPECT_NEAR(*g.heading(2, 1), kSouth, 1e-12);  // the reverse crossing
  EXPECT_NEAR(std::abs(*g.heading(2, 0)), kPi, 1e-12);
  EXPECT_NEAR(*g.heading(0, 2), kEast, 1e-12);
  // A break cuts the edge between viewpaths.
  const std::size_t breaks[] = {3};
  const qn::RegionGraph cut(obs, breaks);
  EXPECT_FALSE(cut.adjacent(1, 2));
}

TEST(QualnavRegionPlanner, JoinsThroughANeighbourOfTheTip) {
  // 0 -> 1 -> 2 -> 3 east, and a detour 1 -> 4 -> 5 -> 3. Goal 3's paths: [3 2], [3 5]; the start's
  // [0 1] has 2 beside its tip: joined at once.
  const HandGraph h({{0, 1, kEast}, {1, 2, kEast}, {2, 3, kEast}, {1, 4, kNorth}, {4, 5, kEast}, {5, 3, kSouth}});
  const auto plan = qn::plan_regions(*h.graph, h.id(0), h.id(3));
  ASSERT_TRUE(plan);
  EXPECT_EQ(h.labels(plan->nodes), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(plan->breadth_first);
  ASSERT_EQ(plan->headings.size(), 3U);
  for (const auto& heading : plan->headings) EXPECT_NEAR(*heading, kEast, 1e-12);
}

TEST(QualnavRegionPlanner, TiesGoToTheLowerIdAndGoalPathsJoinToo) {
  // From 1 two ways lead east with the same heading, through 2 or 3, each three steps to the goal 8.
  const HandGraph h({{0, 1, kEast},
                     {1, 2, kEast},
                     {1, 3, kEast},
                     {2, 4, kEast},
                     {3, 5, kEast},
                     {4, 6, kEast},
                     {5, 7, kEast},
                     {6, 8, kEast},
                     {7, 8, kEast}});
  const auto plan = qn::plan_regions(*h.graph, h.id(0), h.id(8));
  ASSERT_TRUE(plan);
  EXPECT_EQ(h.labels(plan->nodes), (std::vector<int>{0, 1, 2, 4, 6, 8}));
  EXPECT_FALSE(plan->breadth_first);
  // Backwards the goal's paths lead; the same tie picks 6's side (the lower id of 6 and 7).
  const auto back = qn::plan_regions(*h.graph, h.id(8), h.id(0));
  ASSERT_TRUE(back);
  EXPECT_EQ(h.labels(back->nodes), (std::vector<int>{8, 6, 4, 2, 1, 0}));
  EXPECT_NEAR(*back->headings.front(), kWest, 1e-12);
}

TEST(QualnavRegionPlanner, EveryNeighbourOfTheStartLeadsAPath) {
  // The start's north neighbour leads to a dead end; its east one meets the goal's path.
  const HandGraph h({{0, 1, kNorth}, {1, 2, kNorth}, {0, 3, kEast}, {3, 4, kEast}, {4, 5, kEast}});
  const auto plan = qn::plan_regions(*h.graph, h.id(0), h.id(5));
  ASSERT_TRUE(plan);
  EXPECT_EQ(h.labels(plan->nodes), (std::vector<int>{0, 3, 4, 5}));
  EXPECT_FALSE(plan->breadth_first);
}

TEST(QualnavRegionPlanner, BreadthFirstWhenThePathsNeverMeet) {
  // Start 0 -> 1 east; 1 -> 2 east is a dead end, 1 -> 3 north leads round: 3 -> 4 -> 5 -> 8.
  // Goal 9 -> 8 west; 8 -> 7 west is a dead end. Both greedy paths run into their dead ends.
  const HandGraph h({{0, 1, kEast},
                     {1, 2, kEast},
                     {1, 3, kNorth},
                     {3, 4, kEast},
                     {4, 5, kEast},
                     {5, 8, kSouth},
                     {8, 9, kEast},
                     {7, 8, kEast}});
  const auto plan = qn::plan_regions(*h.graph, h.id(0), h.id(9));
  ASSERT_TRUE(plan);
  EXPECT_TRUE(plan->breadth_first);
  EXPECT_EQ(h.labels(plan->nodes), (std::vector<int>{0, 1, 3, 4, 5, 8, 9}));
  // Unreachable: two viewpaths that never share a region.
  const HandGraph apart({{0, 1, kEast}, {2, 3, kEast}});
  EXPECT_FALSE(qn::plan_regions(*apart.graph, apart.id(0), apart.id(3)));
  EXPECT_EQ(qn::plan_regions(*apart.graph, apart.id(2), apart.id(2))->nodes.size(), 1U);
  EXPECT_THROW((void)qn::plan_regions(*apart.graph, 0, 9), std::out_of_range);
}

TEST(QualnavRegionPlanner, EdgeHeadingIsTheBisectorWithoutARecordedCrossing) {
  // Landmarks 0 (0, 100) and 1 (100, 100); from (50, 0) the pair's bisector points north.
  const std::vector<Vector2d> marbles{{0, 100}, {100, 100}};
  std::vector<qn::RegionObservation> obs{qn::observe_regions(panorama(marbles, {50, 0})),
                                         qn::observe_regions(panorama(marbles, {50, 200}))};
  const qn::RegionGraph g(obs);
  ASSERT_EQ(g.nodes().size(), 2U);
  EXPECT_NEAR(*g.heading(0, 1), kNorth, 1e-12);
  EXPECT_NEAR(*g.heading(1, 0), kSouth, 1e-12);
}

TEST(QualnavRegionPlanner, ShortcutNeedsVisibleLpbsAndAProduction) {
  // A B C D spread left to right in front of an observer at the origin facing north.
  const std::vector<Vector2d> marbles{{-300, 100}, {-100, 300}, {100, 300}, {300, 100}};
  const Vector2d here(0, 0);
  const auto view = panorama(marbles, here);
  const qn::RegionNode same{qn::observe_regions(view).signs, {}, {}};
  const qn::RegionShortcut stay = qn::shortcut_to(same, view);
  EXPECT_TRUE(stay.possible);
  EXPECT_TRUE(stay.separating.empty());

  // Across LPB(B, C) only (between them, beyond the pair): b[B C], a production.
  const qn::RegionNode beyond{qn::observe_regions(panorama(marbles, {0, 400})).signs, {}, {}};
  const qn::RegionShortcut through = qn::shortcut_to(beyond, view);
  ASSERT_TRUE(through.possible) << through.reason;
  // Every pair whose side differs at (0, 400): (1, 2) and the pairs of the outer ones with the inner.
  ASSERT_FALSE(through.separating.empty());
  ASSERT_TRUE(through.production);

  // Flip (A, B) and (C, D) only: b[A B] and b[C D] do not intersect in the order A B C D: "–".
  qn::RegionNode apart{same.signs, {}, {}};
  apart.signs[{0, 1}] *= -1;
  apart.signs[{2, 3}] *= -1;
  const qn::RegionShortcut none = qn::shortcut_to(apart, view);
  EXPECT_FALSE(none.possible);
  ASSERT_EQ(none.specifiers.size(), 2U);
  EXPECT_EQ(none.specifiers[0], (qn::HeadingSpecifier{qn::Specifier::b, 0, 1}));
  EXPECT_EQ(none.specifiers[1], (qn::HeadingSpecifier{qn::Specifier::b, 2, 3}));
  EXPECT_NE(none.reason.find("–"), std::string::npos) << none.reason;

  // A target LPB with a landmark out of view.
  qn::RegionNode unseen{same.signs, {}, {}};
  unseen.signs[{1, 7}] = 1;
  EXPECT_FALSE(qn::shortcut_to(unseen, view).possible);
  EXPECT_EQ(qn::shortcut_to(unseen, view).reason, "LPB (1, 7) is not in view");
}

TEST(QualnavRegionPlanner, ShortcutCrossesBeyondTheNearerLandmarkWhenThePairIsNarrow) {
  // A (0, 100) and B (20, 400) seen from the origin about 15° apart: cross beyond the nearer, A.
  const std::vector<Vector2d> marbles{{0, 100}, {-100, 400}};
  const auto view = panorama(marbles, {0, 0});
  qn::RegionNode target{qn::observe_regions(view).signs, {}, {}};
  target.signs[{0, 1}] *= -1;
  const std::map<qn::LandmarkId, double> ranges{{0, 100}, {1, 412}};
  const qn::RegionShortcut s = qn::shortcut_to(target, view, ranges);
  ASSERT_TRUE(s.possible) << s.reason;
  // B (−100, 400) is left of A (0, 100) facing north: the pair is [B A], A the right one: r[B A].
  ASSERT_EQ(s.specifiers.size(), 1U);
  EXPECT_EQ(s.specifiers[0], (qn::HeadingSpecifier{qn::Specifier::r, 1, 0}));
  // Without ranges: b.
  EXPECT_EQ(qn::shortcut_to(target, view).specifiers[0].kind, qn::Specifier::b);
}

TEST(QualnavRegionPlanner, FurthestShortcutAlongAPlan) {
  // Walking north between four landmarks crosses LPBs one after another; from the start every later
  // region of the walk is reachable in one heading (all LPBs in view, productions defined).
  const std::vector<Vector2d> marbles{{-300, 100}, {-100, 300}, {100, 300}, {300, 100}};
  std::vector<qn::RegionObservation> obs;
  for (double y = 0; y <= 600; y += 20) obs.push_back(qn::observe_regions(panorama(marbles, {5, y})));
  const qn::RegionGraph g(obs);
  ASSERT_GE(g.nodes().size(), 3U);
  const auto plan = qn::plan_regions(g, g.node_of_observation().front(), g.node_of_observation().back());
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->nodes.size(), g.nodes().size());  // a walk without returns: every region once
  const auto furthest = qn::furthest_shortcut(g, *plan, 0, panorama(marbles, {5, 0}));
  ASSERT_TRUE(furthest);
  EXPECT_GE(*furthest, 1U);
}

// A panorama's observation and the arrangement agree on every pair at random observers; a walk's
// nodes are orientation regions of the arrangement; a fine walk mostly crosses one LPB at a time.
TEST(QualnavRegionPlanner, ObservationsAreRegionsOfTheArrangement) {
  const std::vector<Vector2d> marbles{{120, 80}, {400, 150}, {260, 420}, {90, 330}, {330, 300}};
  const std::vector<qn::LandmarkId> ids{0, 1, 2, 3, 4};
  const qn::Arrangement arrangement(ids, marbles);
  const qn::OrientationRegions regions(arrangement);
  std::vector<qn::RegionObservation> walk;
  for (double t = 0; t <= 1.0; t += 0.002)
    walk.push_back(qn::observe_regions(panorama(marbles, {20 + 460 * t, 40 + 400 * t * t})));
  const qn::RegionGraph g(walk);
  for (const qn::RegionNode& node : g.nodes()) {
    bool found = false;
    for (const qn::OrientationRegion& r : regions.regions())
      found |= qn::to_pair_signs(arrangement.pairs(), r.signs) == node.signs;
    EXPECT_TRUE(found);
  }
  std::size_t crossings = 0;
  for (std::size_t i = 0; i < g.nodes().size(); ++i) {
    for (const qn::RegionEdge& e : g.nodes()[i].edges) {
      std::size_t differ = 0;
      for (const auto& [pair, sign] : g.nodes()[i].signs) differ += g.nodes()[e.to].signs.at(pair) != sign;
      EXPECT_GE(differ, 1U);
      crossings += differ == 1;
    }
  }
  EXPECT_GE(g.nodes().size(), 5U);
  EXPECT_GT(crossings, 0U);
  const std::vector<qn::LandmarkPair> reversed{{1, 0}};
  EXPECT_EQ(qn::to_pair_signs(reversed, {1}).at({0, 1}), -1);
}
