// Views, parkways and trajectories against brute force and hand-made worlds (park-kender.md §3-4).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <random>

#include "nav/mapmaker/parkways.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"
#include "tests/nav/uniform_world.hpp"

namespace neopipe::nav::mapmaker {
namespace {

using Eigen::Vector2d;

using test_worlds::uniform_world;

TEST(MapViews, VisibleSetsEqualBruteForceAtEveryPlacement) {
  for (const int n : {0, 1, 30, 400}) {
    const Workspace w = uniform_world(n, 300, 7 + n);
    const WorldViews views(w, WindowModel::with_side(50));
    for (std::uint32_t node = 0; node < 4 * w.objects.size(); ++node) {
      const Placement p = Placement::of_node(node);
      std::vector<std::uint32_t> expected;
      for (std::uint32_t i = 0; i < w.objects.size(); ++i) {
        if (views.window().sees(views.origin(p), w.objects[i])) expected.push_back(i);
      }
      const auto got = views.visible(p);
      ASSERT_EQ(std::vector<std::uint32_t>(got.begin(), got.end()), expected) << n << " " << node;
      ASSERT_TRUE(std::binary_search(expected.begin(), expected.end(), p.object));
    }
  }
}

TEST(MapViews, RejectsAMarginThatLeavesTheReferenceOutOfItsWindow) {
  const Workspace w = uniform_world(3, 100, 1);
  EXPECT_THROW(WorldViews(w, WindowModel{50, 0}), MapError);
  EXPECT_THROW(WorldViews(w, WindowModel{50, 25}), MapError);
  EXPECT_THROW(WorldViews(w, WindowModel{-1, 0.1}), MapError);
}

TEST(Parkways, HandMadeWorldHasTheExpectedParkways) {
  // A and B share a window; C is alone in the north-east; D sits near C but not near A or B.
  //   A (100,100)  B (120,130)  C (300,300)  D (330,310)
  const Workspace w{{500, 500}, {{100, 100}, {120, 130}, {300, 300}, {330, 310}}};
  const WorldViews views(w, WindowModel::with_side(50));
  EXPECT_EQ(general_parkways(views), (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2, 3}}));
  // A at SW looks North-East and sees only B; B at NE looks South-West and sees only A.
  const std::vector<ParkwayEdge> obvious = obvious_parkway(views);
  const std::vector<ParkwayEdge> expected{
      {0, Corner::SW, 1}, {1, Corner::NE, 0}, {2, Corner::SW, 3}, {3, Corner::NE, 2}};
  EXPECT_EQ(obvious, expected);
  EXPECT_EQ(isolated_parkway(views), expected);  // one candidate each: isolated = obvious
  EXPECT_EQ(views.qoc(0), 1);
  EXPECT_EQ(views.quadrants(0)[index(Corner::NE)], true);
}

TEST(Parkways, GeneralParkwaysEqualBruteForceComponents) {
  const Workspace w = uniform_world(80, 400, 3);  // ~1.5 neighbours per object: many components
  const WorldViews views(w, WindowModel::with_side(30));
  const std::size_t n = w.objects.size();
  std::vector<std::uint32_t> label(n);
  std::iota(label.begin(), label.end(), 0u);
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        if (i != j && views.window().fit_together(w.objects[i], w.objects[j]) && label[j] < label[i]) {
          label[i] = label[j];
          changed = true;
        }
      }
    }
  }
  std::vector<std::vector<std::uint32_t>> expected;
  std::map<std::uint32_t, std::size_t> slot;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!slot.count(label[i])) {
      slot[label[i]] = expected.size();
      expected.emplace_back();
    }
    expected[slot[label[i]]].push_back(i);
  }
  EXPECT_EQ(general_parkways(views), expected);
  EXPECT_GT(expected.size(), 5u);
  EXPECT_LT(expected.size(), n);
}

TEST(StronglyConnected, EqualsMutualReachabilityOnRandomGraphs) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint32_t n = 1 + rng() % 12;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    const int m = static_cast<int>(rng() % (2 * n + 1));
    for (int e = 0; e < m; ++e) edges.emplace_back(rng() % n, rng() % n);
    std::vector<std::vector<bool>> reach(n, std::vector<bool>(n, false));
    for (std::uint32_t i = 0; i < n; ++i) reach[i][i] = true;
    for (const auto& [a, b] : edges) reach[a][b] = true;
    for (std::uint32_t k = 0; k < n; ++k)
      for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < n; ++j)
          if (reach[i][k] && reach[k][j]) reach[i][j] = true;
    const auto components = strongly_connected_components(n, edges);
    std::vector<int> which(n, -1);
    for (std::size_t c = 0; c < components.size(); ++c) {
      ASSERT_TRUE(std::is_sorted(components[c].begin(), components[c].end()));
      for (const std::uint32_t v : components[c]) which[v] = static_cast<int>(c);
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      ASSERT_GE(which[i], 0);
      for (std::uint32_t j = 0; j < n; ++j) ASSERT_EQ(which[i] == which[j], reach[i][j] && reach[j][i]);
    }
  }
}

TEST(Trajectories, HandMadeSlideFindsTheFirstObjectToEnter) {
  // R at SW (window [97.5,147.5]^2), V east of it: Trajp slides East, Trajn West.
  //   G (200,120) enters East after 200 - 147.5 = 52.5 mm; H (300,100) would enter later;
  //   K (180,90) lies below the window's band and never enters; W (20,110) enters West after
  //   97.5 - 20 = 77.5 mm.
  const Workspace w{{500, 500}, {{100, 100}, {110, 100}, {200, 120}, {300, 100}, {180, 90}, {20, 110}}};
  const WorldViews views(w, WindowModel::with_side(50));
  const Placement from{0, Corner::SW};
  ASSERT_EQ(views.obvious(from), 1u);
  const auto east = trajectory_from(views, from, Description::Obvious, Direction::positive);
  ASSERT_TRUE(east);
  EXPECT_EQ(east->to, 2u);
  EXPECT_NEAR(east->slide, 52.5, 1e-12);
  const auto west = trajectory_from(views, from, Description::Obvious, Direction::negative);
  ASSERT_TRUE(west);
  EXPECT_EQ(west->to, 5u);
  EXPECT_NEAR(west->slide, 77.5, 1e-12);
  // From H at SE looking West... H's window [252.5,302.5]x[97.5,147.5] sees nothing else: no
  // landmark, so no trajectory.
  EXPECT_FALSE(trajectory_from(views, {3, Corner::SE}, Description::Isol, Direction::positive));
}

// Two objects entering at exactly the same slide: the one preferred from the reference (farther,
// then larger x, then larger y) is the goal, whichever id or grid cell it has
// (tests/mutation/mutants.json, N19).
TEST(Trajectories, ExactTiesGoToThePreferredObject) {
  // R at SW (window [97.5,147.5]^2), V east of it: Trajp slides East; both candidates lie on
  // x = 200 and enter after 52.5 mm. The farther from R is (200,130) in the first pair and
  // (200,98) in the second.
  const std::vector<std::pair<Vector2d, Vector2d>> pairs{{{200, 130}, {200, 120}}, {{200, 98}, {200, 101}}};
  for (const auto& [farther, nearer] : pairs) {
    for (const bool farther_first : {true, false}) {
      const Vector2d a = farther_first ? farther : nearer;
      const Vector2d b = farther_first ? nearer : farther;
      const Workspace w{{500, 500}, {{100, 100}, {110, 100}, a, b}};
      const WorldViews views(w, WindowModel::with_side(50));
      const Placement from{0, Corner::SW};
      ASSERT_EQ(views.obvious(from), 1u);
      const auto east = trajectory_from(views, from, Description::Obvious, Direction::positive);
      ASSERT_TRUE(east);
      EXPECT_EQ(east->to, farther_first ? 2u : 3u) << "farther " << farther.transpose();
      EXPECT_EQ(east->slide, 52.5);
    }
  }
}

TEST(Trajectories, LeavingTheWorldWithoutMeetingAnObjectMeansNoTrajectory) {
  const Workspace w{{500, 500}, {{100, 100}, {110, 100}}};
  const WorldViews views(w, WindowModel::with_side(50));
  EXPECT_FALSE(trajectory_from(views, {0, Corner::SW}, Description::Obvious, Direction::positive));
  EXPECT_FALSE(trajectory_from(views, {0, Corner::SW}, Description::Obvious, Direction::negative));
}

TEST(Trajectories, EntryDistanceIsWhereTheObjectCrossesIntoTheOpenWindow) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-200, 200);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
  const WindowModel window = WindowModel::with_side(50);
  int entered = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vector2d start(u(rng), u(rng));
    const double th = angle(rng);
    const Vector2d dir(std::cos(th), std::sin(th));
    const Vector2d p(u(rng), u(rng));
    const auto t = entry_distance(window, start, dir, p);
    if (window.sees(start, p)) {
      ASSERT_FALSE(t);
      continue;
    }
    if (!t) {  // never inside: check along the ray at fine steps
      for (double s = 0; s < 600; s += 0.25) ASSERT_FALSE(window.sees(start + s * dir, p)) << trial;
      continue;
    }
    ++entered;
    ASSERT_FALSE(window.sees(start + (*t - 1e-7) * dir, p)) << trial;
    ASSERT_TRUE(window.sees(start + (*t + 1e-7) * dir, p)) << trial;
  }
  EXPECT_GT(entered, 1000);
  // On the leading edge at the start: not seen (the window is open) and entering at once
  // (tests/mutation/mutants.json, N20).
  EXPECT_EQ(entry_distance(window, {0, 0}, {1, 0}, {50, 25}), 0.0);
  EXPECT_EQ(entry_distance(window, {0, 0}, {0, -1}, {25, 0}), 0.0);
}

TEST(Trajectories, SweepFindsTheSameGoalAsCheckingEveryObject) {
  const Workspace w = uniform_world(500, 600, 9);
  const WorldViews views(w, WindowModel::with_side(40));
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
  std::uniform_real_distribution<double> u(-50, 650);
  int found = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vector2d start(u(rng), u(rng));
    const double th = angle(rng);
    const Vector2d dir(std::cos(th), std::sin(th));
    std::optional<TrajectoryHit> expected;
    for (std::uint32_t i = 0; i < w.objects.size(); ++i) {
      const auto t = entry_distance(views.window(), start, dir, w.objects[i]);
      if (t && (!expected || *t < expected->slide)) expected = TrajectoryHit{i, *t};
    }
    const auto got = first_entering(views.grid(), views.window(), start, dir, start);
    ASSERT_EQ(got.has_value(), expected.has_value()) << trial;
    if (got) {
      ++found;
      ASSERT_EQ(got->object, expected->object) << trial;
      ASSERT_EQ(got->slide, expected->slide);
    }
  }
  EXPECT_GT(found, 2000);
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
