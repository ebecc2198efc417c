// Verification and recovery: a map whose entry leads to the wrong landmark, with a rule that
// brings the navigator back; the same mistake without the rule, or with recovery off, is an aware
// failure. The world is built so that the shared descriptors make the mistake (checked with the
// map-maker's own views first).

#include <gtest/gtest.h>

#include "journey.hpp"
#include "nav/mapmaker/views.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator {
namespace {

using test_rig::Rig;
using test_rig::RigOptions;

constexpr std::size_t S = 0, A = 1, B = 2, D = 3;

// From S held at SW the isolated landmark is B (QOC 3); the map intends A (QOC 2). Held at NW, B
// sees only A, so "(3, NW, Isol)" leads from the mistake back to A. A lies 2 mm nearer S than B does,
// so B's isolation does not hang on a tie that the camera's noise would break either way.
sim::World mistake_world() {
  sim::World w;
  w.size = {300, 300};
  w.objects = {{100, 100}, {138, 105}, {105, 140}, {115, 175}};
  return w;
}

class Recovery : public ::testing::Test {
 protected:
  void SetUp() override {
    const mapmaker::Workspace ws = test_rig::workspace_of(world_);
    const mapmaker::WorldViews views(ws, WindowModel::with_side(50));
    ASSERT_EQ(views.isolated({S, Corner::SW}), B);
    ASSERT_EQ(views.qoc(A), 2);
    ASSERT_EQ(views.qoc(B), 3);
    ASSERT_EQ(views.isolated({B, Corner::NW}), A);
  }
  sim::World world_ = mistake_world();
};

TEST_F(Recovery, ARuleLeadsBackFromTheWrongLandmark) {
  for (const bool errors : {false, true}) {
    RigOptions o;
    if (!errors) o.errors = sim::MotionErrors::none();
    Rig rig(world_, o);
    const CustomMap map = parse_custom_map("((*, SW), (Isol, (3, NW, Isol), (2, -), -))");
    const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, A);
    EXPECT_EQ(j.report.recoveries, 1);
    ASSERT_EQ(j.report.entries.size(), 2u);
    EXPECT_TRUE(j.report.entries[1].verified);
    EXPECT_EQ(j.report.entries[1].measured_qoc, 2);
    EXPECT_EQ(j.report.entries[1].recoveries, 1);
  }
}

TEST_F(Recovery, RecoveryAlsoWorksMidJourney) {
  // The same mistake, then the journey goes on from A: adjusted to NE it sees S alone.
  Rig rig(world_);
  const CustomMap map = parse_custom_map("((*, SW), (Isol, (3, NW, Isol), (2, -), NE), (Obvious, -))");
  const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::SW);
  ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
  EXPECT_EQ(j.final_object, S);
  EXPECT_EQ(j.report.recoveries, 1);
}

// No rule for QOC 3: the paper's navigator (no second candidate) fails aware; with candidates, the
// QOC having proved B wrong, it goes back to S and takes the next most isolated object, A.
TEST_F(Recovery, NoRuleForTheQocMeasuredIsAnAwareFailureOrTheNextCandidate) {
  const CustomMap map = parse_custom_map("((*, SW), (Isol, (2, -), -))");
  for (const int alternatives : {0, 2}) {
    Rig rig(world_);
    rig.config().max_alternatives = alternatives;
    const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::SW);
    EXPECT_EQ(j.report.entries.at(1).measured_qoc, 3);
    EXPECT_FALSE(j.report.entries.at(1).verified);
    EXPECT_EQ(j.report.rule_recoveries, 0);
    if (alternatives == 0) {
      EXPECT_EQ(j.report.ending, Ending::unrecoverable);
      EXPECT_NE(j.report.reason.find("QOC 3"), std::string::npos) << j.report.reason;
      EXPECT_EQ(j.report.entries.size(), 2u);
      EXPECT_EQ(j.report.recoveries, 0);
      continue;
    }
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, A);
    EXPECT_EQ(j.report.backtracks, 1);
    ASSERT_EQ(j.report.entries.size(), 3u);  // entry 1 twice
    EXPECT_EQ(j.report.entries[2].candidate, 1);
    EXPECT_TRUE(j.report.entries[2].verified);
  }
}

TEST_F(Recovery, ADeadEndSendsTheNavigatorBackToThePreviousEntrysNextCandidate) {
  // A forced `lost`: the map means S -> A -> B, but from S the most isolated object is B, and
  // nothing is in view of B held at SE. Back at S the navigator takes the next candidate, A, from
  // which B is the obvious landmark.
  const mapmaker::Workspace workspace = test_rig::workspace_of(world_);  // the views point into it
  const mapmaker::WorldViews views(workspace, WindowModel::with_side(50));
  ASSERT_TRUE(views.visible({B, Corner::SE}).size() == 1);
  ASSERT_EQ(views.obvious({A, Corner::SE}), B);
  const CustomMap map = parse_custom_map("((*, SW), (Isol, SE), (Obvious, -))");
  for (const bool errors : {false, true}) {
    RigOptions o;
    if (!errors) o.errors = sim::MotionErrors::none();
    Rig rig(world_, o);
    const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, B);
    EXPECT_EQ(j.report.backtracks, 1);
    EXPECT_EQ(j.report.recoveries, 1);
  }
  Rig rig(world_);
  rig.config().recovery = false;
  EXPECT_EQ(test_rig::travel(rig, map, S, Corner::SW).report.ending, Ending::lost);
}

TEST_F(Recovery, WithRecoveryOffTheMistakeIsAnAwareFailure) {
  Rig rig(world_);
  rig.config().recovery = false;
  const CustomMap map = parse_custom_map("((*, SW), (Isol, (3, NW, Isol), (2, -), -))");
  const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::SW);
  EXPECT_EQ(j.report.ending, Ending::unrecoverable);
  EXPECT_NE(j.report.reason.find("recovery is off"), std::string::npos) << j.report.reason;
}

TEST_F(Recovery, AMapDescribingNothingInViewIsLost) {
  Rig rig(world_);
  // Held at NE, S sees nothing (everything lies to its North-East): no Obvious landmark.
  const CustomMap map = parse_custom_map("((*, NE), (Obvious, -))");
  const test_rig::Journey j = test_rig::travel(rig, map, S, Corner::NE);
  EXPECT_EQ(j.report.ending, Ending::lost);
  EXPECT_FALSE(j.report.reason.empty());
}

TEST_F(Recovery, ATrajectoryIntoEmptySpaceIsLost) {
  Rig rig(world_);
  rig.config().max_slide = 150;
  // From A held at NE the obvious landmark is S; sliding towards it goes West, into nothing.
  const CustomMap map = parse_custom_map("((*, NE), (Obvious, Trajp, -))");
  const test_rig::Journey j = test_rig::travel(rig, map, A, Corner::NE);
  EXPECT_EQ(j.report.ending, Ending::lost);
  EXPECT_NE(j.report.reason.find("without meeting"), std::string::npos) << j.report.reason;
}

}  // namespace
}  // namespace neopipe::nav::navigator

namespace neopipe::nav::navigator {
namespace {

// The map-maker places objects with errors: an object it counted in view may lie just outside.
TEST(ViewMargin, AnObviousLandmarkJustOutsideTheWindowIsStillTaken) {
  sim::World world;
  world.size = {300, 300};
  world.objects = {{100, 100}, {147.8, 120}};  // the second 0.3 mm beyond the East border with the first at SW
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, -))");
  {
    Rig rig(world);
    const test_rig::Journey j = test_rig::travel(rig, map, 0, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, 1u);
  }
  {
    Rig rig(world);
    rig.config().view_margin = 0;
    const test_rig::Journey j = test_rig::travel(rig, map, 0, Corner::SW);
    EXPECT_EQ(j.report.ending, Ending::lost);
  }
}

}  // namespace
}  // namespace neopipe::nav::navigator

namespace neopipe::nav::navigator {
namespace {

// The survey put an object inside the window that really lies beyond its far edge, too far for the
// camera to see even a cap of it: the navigator looks there before it gives up.
TEST(ViewMargin, AnObviousLandmarkBeyondTheFarEdgeIsFoundByLookingThere) {
  sim::World world;
  world.size = {300, 300};
  // From the first held at SW the window spans x 97.5..147.5: the second lies 3.5 mm beyond its East
  // edge; held at SW, the second sees the third alone.
  world.objects = {{100, 100}, {151, 120}, {170, 150}};
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, SW), (Obvious, -))");
  for (const double margin : {4.5, 0.0}) {
    Rig rig(world);
    rig.config().view_margin = margin;
    const test_rig::Journey j = test_rig::travel(rig, map, 0, Corner::SW);
    if (margin == 0) {
      EXPECT_EQ(j.report.ending, Ending::lost);
      continue;
    }
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, 2u);
    EXPECT_EQ(j.report.backtracks, 0);
  }
}

// S held at SW sees V due East (the direction); the band swept East spans y 97.5..147.5. G lies
// 3 mm beyond it (no cap in view; 120 mm along the track, 50.5 across), Y beside G gives it QOC 1,
// X far East inside the band (QOC 0; 200 along, 20 across).
constexpr std::size_t kBesideS = 0, kBesideG = 2, kBesideX = 4;
sim::World goal_beside_the_band_world() {
  sim::World world;
  world.size = {400, 300};
  world.objects = {{100, 100}, {130, 100}, {220, 150.5}, {240, 170}, {300, 120}};
  return world;
}

// A slide whose goal the survey put inside the swept band passes just beside it, and a farther
// marble enters instead; its QOC proves it wrong. Tried again with the window moved beside the
// track, the slide meets the goal.
TEST(SlideRetry, ASlideThatPassesBesideItsGoalIsTriedAgainBesideTheTrack) {
  const sim::World world = goal_beside_the_band_world();
  constexpr std::size_t kS = kBesideS, kG = kBesideG, kX = kBesideX;
  const mapmaker::Workspace workspace = test_rig::workspace_of(world);  // the views point into it
  const mapmaker::WorldViews views(workspace, WindowModel::with_side(50));
  ASSERT_EQ(views.qoc(kG), 1);
  ASSERT_EQ(views.qoc(kX), 0);
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, Trajp:250, (1, -), -))");
  for (const double offset : {4.0, 0.0}) {
    Rig rig(world);
    rig.config().slide_offset = offset;
    const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
    if (offset == 0) {
      EXPECT_NE(j.report.ending, Ending::arrived);
      continue;
    }
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, kG);
    EXPECT_EQ(j.report.backtracks, 1);
    EXPECT_EQ(j.report.entries.back().candidate, 1);
    EXPECT_TRUE(j.report.entries.back().verified);
  }
}

// The direction's landmark lies just beyond the window's edge, as a cap (the seek takes it from
// there); the slide towards it brings it in first. It is known, never the goal: the slide goes on to
// the marble the map describes. (Found on a 1.5 mm survey, where this one mistake lost 18% of the
// journeys of world 2's survey 2 as unaware failures.)
TEST(SlideDirection, TheDirectionsLandmarkEnteringIsNotTheGoal) {
  sim::World world;
  world.size = {400, 300};
  // S held at SW: the window spans x 97.5..147.5; V lies 1 mm beyond its East edge, so only a cap
  // of it is in view. The track S -> V runs East-North-East; G lies well inside the band it sweeps.
  constexpr std::size_t kS = 0, kV = 1, kG = 2;
  world.objects = {{100, 100}, {148.5, 110}, {260, 150}};
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, Trajp:250, -))");
  Rig rig(world);
  const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
  ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
  EXPECT_NE(j.final_object, kV);
  EXPECT_EQ(j.final_object, kG);
}

// The first marble a slide meets has the goal's QOC count but in another quadrant: the count passes
// it, the quadrants the map names do not, and the navigator goes on to the next newcomer.
TEST(QuadrantPattern, AMistakeWithTheGoalsQocButOtherQuadrantsIsFoundOut) {
  sim::World world;
  world.size = {400, 300};
  // S held at SW sees V due East; the band swept East spans y 97.5..147.5. X enters first, its one
  // neighbour Y to its South-East; G enters next, its one neighbour Z to its North-East. Y and Z lie
  // outside the band and never enter.
  constexpr std::size_t kS = 0, kX = 2, kG = 3;
  world.objects = {{100, 100}, {130, 100}, {200, 120}, {280, 130}, {215, 90}, {295, 150}};
  const mapmaker::Workspace workspace = test_rig::workspace_of(world);  // the views point into it
  const mapmaker::WorldViews views(workspace, WindowModel::with_side(50));
  ASSERT_EQ(views.qoc(kX), 1);
  ASSERT_EQ(views.qoc(kG), 1);
  ASSERT_EQ(format_quadrants(views.quadrant_pattern(kX, 0)), "SE");
  ASSERT_EQ(format_quadrants(views.quadrant_pattern(kG, 0)), "NE");
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, Trajp:250, (1 NE, -), -))");
  for (const bool quadrants : {true, false}) {
    Rig rig(world);
    rig.config().quadrants = quadrants;
    const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    if (!quadrants) {
      EXPECT_EQ(j.final_object, kX);  // the count alone takes the mistake
      continue;
    }
    EXPECT_EQ(j.final_object, kG);
    EXPECT_EQ(j.report.backtracks, 1);
    EXPECT_EQ(j.report.entries.back().candidate, 1);
    EXPECT_TRUE(j.report.entries.back().verified);
  }
}

}  // namespace
}  // namespace neopipe::nav::navigator

namespace neopipe::nav::navigator {
namespace {

// The map says where a slide's goal enters (SlideGoal): a marble entering well before that place is
// passed by, where the paper's navigator takes the first newcomer whatever it is.
TEST(SlideGoal, AMarbleEnteringBeforeTheGoalsPlaceIsPassedBy) {
  sim::World world;
  world.size = {400, 300};
  // S held at SW sees V due East (the direction); I enters the band first (90 mm along, 40 across),
  // G later (160 along, 20 across).
  constexpr std::size_t kS = 0, kI = 2, kG = 3;
  world.objects = {{100, 100}, {130, 100}, {190, 140}, {260, 120}};
  for (const bool goal_place : {true, false}) {
    Rig rig(world);
    const CustomMap map = parse_custom_map(goal_place ? "((*, SW), (Obvious, Trajp:300@160/20~8/8, -))"
                                                      : "((*, SW), (Obvious, Trajp:300, -))");
    const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    EXPECT_EQ(j.final_object, goal_place ? kG : kI);
    EXPECT_EQ(j.report.backtracks, 0);
  }
}

// A marble entering beyond the goal's place says the goal went by beside the window: the navigator
// tries the slide again beside the track, where the goal enters, without any QOC to tell it. With
// the check off (NavigatorConfig::slide_goals) it takes the far marble and never knows.
TEST(SlideGoal, AMarbleEnteringBeyondTheGoalsPlaceSendsTheSlideBesideTheTrack) {
  const sim::World world = goal_beside_the_band_world();
  constexpr std::size_t kS = kBesideS, kG = kBesideG, kX = kBesideX;
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, Trajp:250@120/50~8/8, -))");
  for (const bool check : {true, false}) {
    Rig rig(world);
    rig.config().slide_offset = 4;
    rig.config().slide_goals = check;
    const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
    ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
    if (!check) {
      EXPECT_EQ(j.final_object, kX);
      continue;
    }
    EXPECT_EQ(j.final_object, kG);
    EXPECT_EQ(j.report.backtracks, 1);
    EXPECT_EQ(j.report.entries.back().candidate, 1);
  }
}

// Nothing enters where the goal should, and nothing after it either, before the map's bound: the
// goal went by as surely, and the slide is tried again beside the track rather than the landmark
// before it doubted.
TEST(SlideGoal, NothingWhereTheGoalShouldBeIsTriedAgainBesideTheTrack) {
  sim::World world = goal_beside_the_band_world();
  world.objects.pop_back();  // no X: nothing enters after the goal's place either
  constexpr std::size_t kS = kBesideS, kG = kBesideG;
  const CustomMap map = parse_custom_map("((*, SW), (Obvious, Trajp:160@120/50~8/8, -))");
  Rig rig(world);
  rig.config().slide_offset = 4;
  const test_rig::Journey j = test_rig::travel(rig, map, kS, Corner::SW);
  ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason;
  EXPECT_EQ(j.final_object, kG);
  EXPECT_EQ(j.report.entries.back().candidate, 1);
}

}  // namespace
}  // namespace neopipe::nav::navigator
