// The reliable, error-detectable and error-recoverable parkways against brute force on random
// worlds and a hand-made one (park-kender.md §3, §7).

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "nav/mapmaker/parkway_quality.hpp"
#include "nav/mapmaker/view_agreement.hpp"
#include "tests/nav/uniform_world.hpp"

namespace neopipe::nav::mapmaker {
namespace {

using test_worlds::uniform_world;

// QOC by its definition: for each quadrant, is any other object in view with L held opposite it.
int brute_force_qoc(const Workspace& w, const WindowModel& window, std::uint32_t landmark) {
  int count = 0;
  for (const Corner q : kCorners) {
    const Eigen::Vector2d origin = window.origin(w.objects[landmark], opposite(q));
    for (std::uint32_t i = 0; i < w.objects.size(); ++i) {
      if (i != landmark && window.sees(origin, w.objects[i])) {
        ++count;
        break;
      }
    }
  }
  return count;
}

std::vector<std::uint32_t> brute_force_visible(const Workspace& w, const WindowModel& window, const Placement& p) {
  std::vector<std::uint32_t> out;
  const Eigen::Vector2d origin = window.origin(w.objects[p.object], p.corner);
  for (std::uint32_t i = 0; i < w.objects.size(); ++i) {
    if (window.sees(origin, w.objects[i])) out.push_back(i);
  }
  return out;
}

bool contains(const std::vector<ParkwayEdge>& edges, const ParkwayEdge& e) {
  return std::find(edges.begin(), edges.end(), e) != edges.end();
}

TEST(ParkwayQuality, TwoObjectsMakeObviousEdgesThatAreReliableAndTriviallyVerified) {
  const Workspace w{{300, 300}, {{100, 100}, {120, 130}}};
  const WorldViews views(w, WindowModel::with_side(50));
  const auto edges = parkway_edge_qualities(views, NavigatorErrors{});
  // 0 -> 1 holding 0 at SW, 1 -> 0 holding 1 at NE; once as Obvious, once as Isol.
  ASSERT_EQ(edges.size(), 4U);
  for (const ParkwayEdgeQuality& e : edges) {
    EXPECT_EQ(e.reliability, 1.0);
    EXPECT_EQ(e.verifiability, Verifiability::trivial);
  }
  const QualifiedParkways q = qualify_parkways(edges, 0.99);
  const std::vector<ParkwayEdge> expected{{0, Corner::SW, 1}, {1, Corner::NE, 0}};
  for (const ParkwaySubgraph* g : {&q.reliable, &q.detectable, &q.recoverable}) {
    EXPECT_EQ(g->obvious, expected);
    EXPECT_EQ(g->isolated, expected);
  }
}

TEST(ParkwayQuality, SubgraphsMatchTheirDefinitionsByBruteForce) {
  int undetectable = 0;
  int unrecoverable = 0;
  int unreliable = 0;
  for (const int n : {20, 120, 300}) {
    const Workspace w = uniform_world(n, 300, 11 + n);
    const WindowModel window = WindowModel::with_side(50);
    const WorldViews views(w, window);
    NavigatorErrors errors;
    errors.sigma = 2.0;
    const double threshold = 0.9;
    const auto edges = parkway_edge_qualities(views, errors);
    const QualifiedParkways q = qualify_parkways(edges, threshold);
    ASSERT_EQ(edges.size(), obvious_parkway(views).size() + isolated_parkway(views).size());
    for (const ParkwayEdgeQuality& e : edges) {
      const auto visible = brute_force_visible(w, window, {e.edge.from, e.edge.corner});
      const bool obvious = e.description == Description::Obvious;
      if (obvious) {
        ASSERT_EQ(visible.size(), 2U);
      }
      const int landmark_qoc = brute_force_qoc(w, window, e.edge.to);
      bool qoc_unique = true;
      for (const std::uint32_t id : visible) {
        if (!obvious && id != e.edge.from && id != e.edge.to && brute_force_qoc(w, window, id) == landmark_qoc) {
          qoc_unique = false;
        }
      }
      const double reliability = selection_reliability(static_cast<int>(visible.size()), errors.sigma, window.side) *
                                 view_agreement(views, {e.edge.from, e.edge.corner}, e.description, errors.sigma);
      EXPECT_DOUBLE_EQ(e.reliability, reliability);
      const auto& reliable = obvious ? q.reliable.obvious : q.reliable.isolated;
      const auto& detectable = obvious ? q.detectable.obvious : q.detectable.isolated;
      const auto& recoverable = obvious ? q.recoverable.obvious : q.recoverable.isolated;
      EXPECT_EQ(contains(reliable, e.edge), reliability >= threshold);
      EXPECT_EQ(contains(detectable, e.edge), qoc_unique) << e.edge.from << "->" << e.edge.to;
      if (contains(recoverable, e.edge)) {
        EXPECT_TRUE(qoc_unique);
      }
      undetectable += qoc_unique ? 0 : 1;
      unrecoverable += (qoc_unique && !e.recoverable()) ? 1 : 0;
      unreliable += reliability < threshold ? 1 : 0;
    }
  }
  // The worlds are dense enough that every sub-graph is a proper one.
  EXPECT_GT(undetectable, 0);
  EXPECT_GT(unrecoverable, 0);
  EXPECT_GT(unreliable, 0);
}

TEST(ParkwayQuality, ThresholdBoundsSelectTheWholeGraphOrTheCertainEdges) {
  const Workspace w = uniform_world(150, 300, 5);
  const WorldViews views(w, WindowModel::with_side(50));
  const auto edges = parkway_edge_qualities(views, NavigatorErrors{});
  const QualifiedParkways all = qualify_parkways(edges, 0.0);
  EXPECT_EQ(all.reliable.obvious, obvious_parkway(views));
  EXPECT_EQ(all.reliable.isolated, isolated_parkway(views));
  const QualifiedParkways certain = qualify_parkways(edges, 1.0);
  for (const ParkwayEdge& e : certain.reliable.isolated) EXPECT_EQ(views.visible({e.from, e.corner}).size(), 2U);
  EXPECT_THROW(qualify_parkways(edges, 1.5), MapError);
  EXPECT_THROW(qualify_parkways(edges, -0.1), MapError);
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
