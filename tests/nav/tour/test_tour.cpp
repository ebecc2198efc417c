// TOUR (qualnav.md §8): the worked example of §10, the boundary rules in both turn directions and
// directions of travel, merging of places and paths, the metric map and its distortion switches,
// and schema retrieval by completeness (Table 2).

#include <gtest/gtest.h>

#include "nav/tour/actions.hpp"
#include "nav/tour/cognitive_map.hpp"
#include "nav/tour/schemas.hpp"

namespace neopipe::nav::tour {
namespace {

TEST(TourTurns, KindsFollowTheSpecSigns) {
  EXPECT_EQ(turn_kind(-90), TurnKind::right);
  EXPECT_EQ(turn_kind(90), TurnKind::left);
  EXPECT_EQ(turn_kind(180), TurnKind::around);
  EXPECT_EQ(turn_kind(-180), TurnKind::around);
  EXPECT_EQ(turn_kind(0), TurnKind::none);
  EXPECT_EQ(turn_kind(270), TurnKind::right);  // wrapped to −90
  EXPECT_EQ(turn_kind(175, 10), TurnKind::around);
  EXPECT_EQ(turn_kind(175), TurnKind::left);
}

// §10: Travel 50, Turn −90, Travel 30 -> 3 places, 2 paths, P3 in right(path1), P1 in right(path2),
// localposition(P2, path1) = 50.
TEST(TourMap, WorkedExampleOfTheSpec) {
  CognitiveMap map;
  map.assimilate(1, Travel{50, 0.0}, 2);
  map.assimilate(2, Turn{-90}, 3);
  map.assimilate(3, Travel{30, 0.0}, 4);
  EXPECT_EQ(map.places().size(), 3U);
  EXPECT_EQ(map.paths().size(), 2U);
  const PlaceId p1 = *map.place(1);
  const PlaceId p2 = *map.place(2);
  const PlaceId p3 = *map.place(4);
  EXPECT_EQ(*map.place(3), p2);
  const PathId path1 = *map.path(1);
  const PathId path2 = *map.path(3);
  EXPECT_NE(path1, path2);
  EXPECT_EQ(*map.path(2), path1);
  EXPECT_EQ(*map.path(4), path2);
  EXPECT_TRUE(map.in_right(p3, path1));
  EXPECT_TRUE(map.in_right(p1, path2));
  EXPECT_FALSE(map.in_left(p3, path1));
  EXPECT_DOUBLE_EQ(*map.local_position(p2, path1), 50);
  EXPECT_DOUBLE_EQ(*map.local_position(p1, path1), 0);
  EXPECT_EQ(*map.order(p1, p2, path1), 1);
  EXPECT_DOUBLE_EQ(*map.path_distance(p1, p2, path1), 50);
  EXPECT_DOUBLE_EQ(*map.local_heading(3), -90);
  EXPECT_DOUBLE_EQ(map.heading(4)->lo, -90);
  EXPECT_DOUBLE_EQ(map.heading(4)->hi, -90);
}

TEST(TourMap, LeftTurnMirrors) {
  CognitiveMap map;
  map.assimilate(1, Travel{50, 0.0}, 2);
  map.assimilate(2, Turn{90}, 3);
  map.assimilate(3, Travel{30, 0.0}, 4);
  EXPECT_TRUE(map.in_left(*map.place(4), *map.path(1)));
  EXPECT_TRUE(map.in_left(*map.place(1), *map.path(3)));
}

TEST(TourMap, TravelAgainstAPathsDirectionFlipsTheSide) {
  CognitiveMap map;
  // Path 1 first travelled 10 -> 11 (+1); then travelled backwards by view 12 (turn around at 11).
  map.assimilate(10, Travel{40, 0.0}, 11);
  map.assimilate(11, Turn{180}, 12);
  EXPECT_EQ(*map.path(12), *map.path(10));
  EXPECT_EQ(*map.direction(12), -1);
  map.assimilate(12, Travel{40, 0.0}, 13);  // back to the first place's position on the path
  EXPECT_DOUBLE_EQ(*map.local_position(*map.place(13), *map.path(10)), 0);
  map.assimilate(13, Turn{-90}, 14);
  map.assimilate(14, Travel{20, 0.0}, 15);
  // Direction −1 along path 1, right turn: the new place lies in left(path 1).
  EXPECT_TRUE(map.in_left(*map.place(15), *map.path(10)));
  EXPECT_FALSE(map.in_right(*map.place(15), *map.path(10)));
}

TEST(TourMap, AroundAddsNoBoundary) {
  CognitiveMap map;
  map.assimilate(1, Travel{50, 0.0}, 2);
  map.assimilate(2, Turn{180}, 3);
  map.assimilate(3, Travel{50, 0.0}, 4);
  for (const PathId p : map.paths()) {
    for (const PlaceId q : map.places()) {
      EXPECT_FALSE(map.in_left(q, p) || map.in_right(q, p));
    }
  }
}

TEST(TourMap, ARevisitedViewMergesPlacesAndTheRouteUsesTheBoundary) {
  CognitiveMap map;
  // A square walked with right turns: 1 -(N)-> 2, right, -(E)-> 4, right, -(S)-> 6, right, -(W)-> 8 = 1's place.
  map.assimilate(1, Travel{10, 0.0}, 2);
  map.assimilate(2, Turn{-90}, 3);
  map.assimilate(3, Travel{10, 0.0}, 4);
  map.assimilate(4, Turn{-90}, 5);
  map.assimilate(5, Travel{10, 0.0}, 6);
  map.assimilate(6, Turn{-90}, 7);
  map.assimilate(7, Travel{10, 0.0}, 8);
  EXPECT_EQ(map.places().size(), 5U);  // the fifth is the first again, which TOUR cannot know yet
  map.assimilate(8, Turn{-90}, 1);     // ... until the view repeats: same place
  EXPECT_EQ(map.places().size(), 4U);
  EXPECT_EQ(*map.place(8), *map.place(1));
  const PlaceId a = *map.place(2);
  const PlaceId b = *map.place(6);
  const std::vector<PlaceId> r = map.route(a, b);
  ASSERT_GE(r.size(), 3U);
  EXPECT_EQ(r.front(), a);
  EXPECT_EQ(r.back(), b);
  EXPECT_EQ(map.heading_conflicts(), 0);
  // Around the square the orientation frame returns to where it started.
  EXPECT_DOUBLE_EQ(map.heading(1)->lo, 0);
}

TEST(TourMap, OrientationFrameIntervalsAndDistortionSwitches) {
  CognitiveMap plain;
  plain.assimilate(1, Travel{10, std::nullopt}, 2);
  EXPECT_DOUBLE_EQ(plain.heading(2)->width(), 360);  // Δθ unknown: [−180°, 180°]
  plain.assimilate(2, Turn{-85}, 3);
  EXPECT_DOUBLE_EQ(*plain.local_heading(3), -85);
  EXPECT_FALSE(plain.distance(*plain.place(1), *plain.place(2)).has_value());

  TourSettings s;
  s.heuristics = {true, 15, true, true};
  CognitiveMap distorted(s);
  distorted.assimilate(1, Travel{10, 12.0}, 2);
  EXPECT_DOUBLE_EQ(distorted.heading(2)->width(), 0);  // (2) Δθ = 0
  EXPECT_DOUBLE_EQ(distorted.heading(2)->lo, 0);
  distorted.assimilate(2, Turn{-85}, 3);
  EXPECT_DOUBLE_EQ(*distorted.local_heading(3), -90);                                   // (1) a right angle
  EXPECT_DOUBLE_EQ(*distorted.distance(*distorted.place(1), *distorted.place(2)), 10);  // (3)
}

TEST(TourSchemas, RetrievalDegradesWithCompleteness) {
  ProceduralMap m;
  // A complete route 1 -A-> 2 -B-> 3 toward goal 3.
  m.add_route({1, 2, 3}, {Travel{10, 0.0}, Turn{-90}});
  // A schema whose result was lost, and one whose goal was lost.
  m.add({7, 5, Travel{20, 0.0}, std::nullopt});
  m.add({std::nullopt, 5, Turn{90}, 6});

  const auto step = m.follow_and_describe(3, 1);
  ASSERT_TRUE(step.has_value());
  EXPECT_EQ(step->second, 2U);
  EXPECT_EQ(m.describe(3, 1).size(), 2U);
  EXPECT_TRUE(m.follow(7, 5).has_value());                // (G, V) -> A
  EXPECT_FALSE(m.follow_and_describe(7, 5).has_value());  // but not (G, V) -> (A, V')
  EXPECT_TRUE(m.describe(7, 5).empty());                  // "I could take you there, but I can't tell you how"
  EXPECT_EQ(*m.predict(5, Turn{90}), 6U);                 // (V, A) -> V'
  EXPECT_FALSE(m.predict(5, Turn{-90}).has_value());
  EXPECT_TRUE(m.known(6));  // V -> known
  EXPECT_FALSE(m.known(99));
}

TEST(TourSchemas, TheMostCommonSchemaWinsWithoutAGoal) {
  ProceduralMap m;
  m.add({std::nullopt, 1, Travel{10, 0.0}, 2});
  m.add({std::nullopt, 1, Travel{10, 0.0}, 3});
  m.add({std::nullopt, 1, Travel{10, 0.0}, 3});
  EXPECT_EQ(*m.predict(1, Travel{10, 0.0}), 3U);
}

}  // namespace
}  // namespace neopipe::nav::tour
