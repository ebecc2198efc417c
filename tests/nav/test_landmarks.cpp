// The landmark descriptors shared by the map-maker and the navigator (park-kender.md §3).

#include <gtest/gtest.h>

#include <vector>

#include "nav/common/landmarks.hpp"
#include "nav/common/window.hpp"

namespace neopipe::nav {
namespace {

using Eigen::Vector2d;

// The paper's worked example (§5.6.2, Fig. 20): four objects whose c-values are 4, 2, 2, 3, so A is
// the most isolated. The figure's coordinates are not in the text; these points give its ranks:
// B and C are each other's nearest (mnv 2), D's nearest is C, which ranks D second (mnv 3), and
// A's nearest is D, which ranks A last (mnv 1 + 3 = 4).
TEST(Landmarks, PapersWorkedExampleCValues) {
  const std::vector<Vector2d> points{{7, 0}, {0, 0}, {1, 0}, {3, 0}};  // A, B, C, D
  EXPECT_EQ(c_values({points, 1}), (std::vector<int>{4, 2, 2, 3}));
  EXPECT_EQ(isolated_landmark({points, 1}), 0u);  // A, seen from B
  EXPECT_EQ(isolated_landmark({points, 2}), 0u);  // and from C
  // Seen from A the reference is excluded: D (c-value 3) is the most isolated of the rest.
  EXPECT_EQ(isolated_landmark({points, 0}), 3u);
}

TEST(Landmarks, ObviousOnlyWithExactlyOneOtherObject) {
  const std::vector<Vector2d> one{{0, 0}};
  const std::vector<Vector2d> two{{0, 0}, {3, 4}};
  const std::vector<Vector2d> three{{0, 0}, {3, 4}, {10, 1}};
  EXPECT_FALSE(obvious_landmark({one, 0}));
  EXPECT_EQ(obvious_landmark({two, 0}), 1u);
  EXPECT_EQ(obvious_landmark({two, 1}), 0u);
  EXPECT_FALSE(obvious_landmark({three, 0}));
  EXPECT_FALSE(isolated_landmark({one, 0}));
  EXPECT_EQ(isolated_landmark({two, 0}), 1u);
}

TEST(Landmarks, TiesGoToTheCandidateFarthestFromTheReferenceThenLargerXThenLargerY) {
  // Two mutually nearest pairs: every candidate has c-value 2, so the farthest one wins.
  const std::vector<Vector2d> pairs{{0, 0}, {1, 0}, {20, 0}, {20, 1}};
  EXPECT_EQ(c_values({pairs, 0}), (std::vector<int>{2, 2, 2, 2}));
  EXPECT_EQ(isolated_landmark({pairs, 0}), 3u);
  // The far pair equally far from the reference: larger x wins, then larger y.
  const std::vector<Vector2d> across{{0, 0}, {0, 1}, {3, 20}, {-3, 20}};
  EXPECT_EQ(isolated_landmark({across, 0}), 2u);
  const std::vector<Vector2d> along{{0, 0}, {0, 1}, {20, -3}, {20, 3}};
  EXPECT_EQ(isolated_landmark({along, 0}), 3u);
}

TEST(Landmarks, DistanceTiesInsideARankingGoToThePreferredObject) {
  // A square seen from its south-west corner: the ties in each ranking are broken by preference
  // (farther from the reference, then larger x), which makes the north-west corner the only one
  // whose nearest neighbours do not rank it first.
  const std::vector<Vector2d> square{{0, 0}, {10, 0}, {0, 10}, {10, 10}};
  EXPECT_EQ(c_values({square, 0}), (std::vector<int>{3, 2, 3, 2}));
  EXPECT_EQ(isolated_landmark({square, 0}), 2u);
}

TEST(Landmarks, SelectionIsInvariantToTranslationAsTheNavigatorSeesWindowCoordinates) {
  const std::vector<Vector2d> world{{101, 203}, {120, 210}, {111, 240}, {140, 230}, {143, 236}};
  std::vector<Vector2d> window;
  for (const Vector2d& p : world) window.push_back(p - Vector2d(98.5, 200.5));
  for (std::size_t ref = 0; ref < world.size(); ++ref) {
    EXPECT_EQ(isolated_landmark({world, ref}), isolated_landmark({window, ref})) << ref;
  }
}

// The extended language (docs/navigation.md, "Descriptions"): Far is the paper's preferred object,
// Near the nearest to the reference, and the ranking behind each is its list of fallbacks.
TEST(Landmarks, FarAndNearRankByDistanceFromTheReference) {
  const std::vector<Vector2d> points{{0, 0}, {5, 0}, {0, 12}, {20, 1}, {3, -2}};
  const View view{points, 0};
  EXPECT_EQ(select_landmark(Description::Far, view), 3u);
  EXPECT_EQ(select_landmark(Description::Far, view), select_landmark(Description::Any, view));
  EXPECT_EQ(select_landmark(Description::Near, view), 4u);
  EXPECT_EQ(ranked_landmarks(Description::Far, view), (std::vector<std::size_t>{3, 2, 1, 4}));
  EXPECT_EQ(ranked_landmarks(Description::Near, view), (std::vector<std::size_t>{4, 1, 2, 3}));
  // Equally near: the larger x, then the larger y, as for Far's ties.
  const std::vector<Vector2d> ring{{0, 0}, {-5, 0}, {0, 5}, {5, 0}, {0, -5}};
  EXPECT_EQ(ranked_landmarks(Description::Near, {ring, 0}), (std::vector<std::size_t>{3, 2, 4, 1}));
  // Nothing but the reference: nothing to select.
  const std::vector<Vector2d> alone{{0, 0}};
  EXPECT_FALSE(select_landmark(Description::Near, {alone, 0}));
  EXPECT_FALSE(select_landmark(Description::Far, {alone, 0}));
}

TEST(Landmarks, DescriptionNamesRoundTrip) {
  for (const Description d :
       {Description::Obvious, Description::Isol, Description::Any, Description::Far, Description::Near}) {
    EXPECT_EQ(parse_description(description_name(d)), d);
  }
  EXPECT_EQ(description_name(Description::Far), "Far");
  EXPECT_EQ(description_name(Description::Near), "Near");
  EXPECT_FALSE(parse_description("near"));
  EXPECT_FALSE(parse_description("Farthest"));
}

TEST(Window, CornerPlacementsHoldTheLandmarkInsetByTheMargin) {
  const WindowModel w = WindowModel::with_side(50);
  EXPECT_DOUBLE_EQ(w.margin, 2.5);
  const Vector2d l{100, 200};
  for (const Corner c : kCorners) {
    const Vector2d o = w.origin(l, c);
    EXPECT_TRUE(w.sees(o, l)) << corner_name(c);
    EXPECT_TRUE(((l - o) - w.corner_point(c)).norm() < 1e-12) << corner_name(c);
  }
  EXPECT_EQ(w.origin(l, Corner::SW), Vector2d(97.5, 197.5));
  EXPECT_EQ(w.origin(l, Corner::NE), Vector2d(52.5, 152.5));
  // Holding L at SW looks North-East.
  EXPECT_TRUE(w.sees(w.origin(l, Corner::SW), l + Vector2d(40, 40)));
  EXPECT_FALSE(w.sees(w.origin(l, Corner::SW), l + Vector2d(-3, 10)));
  EXPECT_EQ(opposite(Corner::SW), Corner::NE);
  EXPECT_EQ(parse_corner("NW"), Corner::NW);
  EXPECT_FALSE(parse_corner("N"));
}

TEST(Window, GeneralParkwayEdgeNeedsBothOffsetsBelowTheReach) {
  const WindowModel w = WindowModel::with_side(50);  // reach 45
  EXPECT_TRUE(w.fit_together({0, 0}, {44.9, -44.9}));
  EXPECT_FALSE(w.fit_together({0, 0}, {45, 0}));
  EXPECT_FALSE(w.fit_together({0, 0}, {1, 45.1}));
}

}  // namespace
}  // namespace neopipe::nav
