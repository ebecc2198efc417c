// The visual memory (qualnav.md §7): links along and across hand-made viewpaths, and A* over them
// against an exhaustive search on small graphs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "nav/qualnav/metric/visual_memory.hpp"

namespace {

namespace q = neopipe::nav::qualnav;
using Eigen::Vector2d;

q::Viewframe view_at(const Vector2d& p, const std::vector<Vector2d>& landmarks) {
  std::vector<q::ViewedLandmark> v;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const Vector2d d = landmarks[i] - p;
    const double r = d.norm();
    v.push_back({static_cast<q::LandmarkId>(i), std::atan2(d.y(), d.x()), 0.0035, r, r / 1.02, r * 1.02});
  }
  return q::make_viewframe(v, 0);
}

std::vector<q::Viewframe> viewpath(const Vector2d& from, const Vector2d& to, const std::vector<Vector2d>& l) {
  std::vector<q::Viewframe> out;
  const double length = (to - from).norm();
  const int n = static_cast<int>(std::floor(length / q::kViewpathSpacingMm));
  for (int i = 0; i <= n; ++i) out.push_back(view_at(from + (to - from) * (i * q::kViewpathSpacingMm / length), l));
  return out;
}

const std::vector<Vector2d> kLandmarks = {{0, 0}, {300, 0}, {300, 300}, {0, 300}, {150, 400}};

TEST(VisualMemory, LinksAlongAViewpathAndAcrossNearOnes) {
  q::VisualMemory m;
  m.add_viewpath(viewpath({50, 50}, {250, 50}, kLandmarks));     // 11 viewframes
  m.add_viewpath(viewpath({150, 120}, {150, 260}, kLandmarks));  // 8, crossing near (150, 120)
  m.add_viewpath(viewpath({50, 280}, {60, 280}, kLandmarks));    // 1, far from the first
  ASSERT_EQ(m.nodes().size(), 20U);
  EXPECT_EQ(m.viewpaths(), 3U);
  for (std::size_t i = 0; i < m.nodes().size(); ++i) {
    for (const q::MemoryLink& e : m.links()[i]) {
      const q::MemoryNode& a = m.nodes()[i];
      const q::MemoryNode& b = m.nodes()[e.to];
      if (a.viewpath == b.viewpath) {
        EXPECT_EQ(std::max(a.index, b.index) - std::min(a.index, b.index), 1U);
        EXPECT_NEAR(e.cost, 20, 3);
      } else {
        EXPECT_LE(e.cost, q::kLinkDistanceMm);
      }
    }
  }
  // Node 5 (150, 50) and the second path's first (150, 120) are 70 mm apart: linked.
  const auto& from5 = m.links()[5];
  EXPECT_TRUE(std::any_of(from5.begin(), from5.end(), [](const q::MemoryLink& e) { return e.to == 11; }));
  // The third path's viewframe (50, 280) is more than 150 mm from all of the first path's.
  for (const q::MemoryLink& e : m.links()[19]) EXPECT_GE(e.to, 11U);
}

TEST(VisualMemory, AStarTakesTheShortcutAcrossViewpaths) {
  q::VisualMemory m;
  m.add_viewpath(viewpath({50, 50}, {250, 50}, kLandmarks));
  m.add_viewpath(viewpath({150, 120}, {150, 260}, kLandmarks));
  // From the first path's start to the second's end: along path 1 to near x = 150, across, up.
  const std::vector<std::size_t> plan = q::plan_over_memory(m, 0, m.nodes().size() - 1);
  ASSERT_GE(plan.size(), 2U);
  EXPECT_EQ(plan.front(), 0U);
  EXPECT_EQ(plan.back(), m.nodes().size() - 1);
  EXPECT_LT(q::path_cost(m.links(), plan), 380.0);  // 100 along, 70 across, 140 up = 310 by the routes
  EXPECT_TRUE(std::none_of(plan.begin(), plan.end(), [](std::size_t n) { return n > 5 && n < 11; }));
}

// A* with a zero heuristic against Bellman-Ford on random graphs: same cost.
TEST(AStar, MatchesAnExhaustiveSearch) {
  std::mt19937 rng(3);
  for (int g = 0; g < 30; ++g) {
    const std::size_t n = 12;
    std::vector<std::vector<q::MemoryLink>> graph(n);
    std::uniform_real_distribution<double> cost(1, 10);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (rng() % 4 != 0) continue;
        const double c = cost(rng);
        graph[i].push_back({j, c});
        graph[j].push_back({i, c});
      }
    }
    std::vector<double> d(n, std::numeric_limits<double>::infinity());
    d[0] = 0;
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t u = 0; u < n; ++u) {
        for (const auto& e : graph[u]) d[e.to] = std::min(d[e.to], d[u] + e.cost);
      }
    }
    const auto path = q::astar(graph, 0, n - 1, [](std::size_t) { return 0.0; });
    if (std::isinf(d[n - 1])) {
      EXPECT_TRUE(path.empty());
    } else {
      ASSERT_FALSE(path.empty());
      EXPECT_NEAR(q::path_cost(graph, path), d[n - 1], 1e-9);
    }
  }
}

}  // namespace
