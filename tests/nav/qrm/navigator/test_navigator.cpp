// QRM's navigator (nav/qrm/navigator, spec qrm.md §8) with a fake sensor and arm: the tool is a
// point with a heading, the eye reports every landmark's exact bearing in the tool frame and its
// distance, the arm moves exactly. The §8 example's route, the detour round a marble in the way,
// and the failures (no path, target lost, step limit, a refused move).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "nav/qrm/navigator/local_path.hpp"
#include "nav/qrm/navigator/navigator.hpp"
#include "nav/qrm/rng.hpp"

namespace {

namespace q = neopipe::nav::qrm;
using Eigen::Vector2d;

constexpr double kDegree = std::numbers::pi / 180;

// The truth of the fake world: landmark positions and the tool's pose.
struct FakeWorld {
  explicit FakeWorld(std::vector<Vector2d> l) : landmarks(std::move(l)) {}
  std::vector<Vector2d> landmarks;
  Vector2d tool{0, 0};
  double heading = 0;  ///< rad: the sensor's zero direction, unknown to the navigator
  std::vector<Vector2d> track;
  double least_gap = 1e9;  ///< nearest the tool came to a landmark's centre, mm
  void note() {
    track.push_back(tool);
    for (const Vector2d& l : landmarks) least_gap = std::min(least_gap, (l - tool).norm());
  }
};

class FakeEye final : public q::Eye {
 public:
  explicit FakeEye(FakeWorld& w) : w_(w) {}
  std::set<std::uint32_t> hidden;  ///< never seen
  std::vector<neopipe::nav::PanoramaSighting> look() override {
    std::vector<neopipe::nav::PanoramaSighting> out;
    for (std::uint32_t i = 0; i < w_.landmarks.size(); ++i) {
      if (hidden.contains(i)) continue;
      const Vector2d d = w_.landmarks[i] - w_.tool;
      double b = (std::atan2(d.y(), d.x()) - w_.heading) / kDegree;
      b = std::fmod(b + 720.0, 360.0);
      neopipe::nav::PanoramaSighting s;
      s.id = i;
      s.bearing_deg = b;
      s.range_mm = d.norm();
      s.range_lo_mm = s.range_mm / 1.5;
      s.range_hi_mm = s.range_mm * 1.5;
      out.push_back(s);
    }
    return out;
  }

 private:
  FakeWorld& w_;
};

class FakeArm final : public neopipe::nav::Arm {
 public:
  explicit FakeArm(FakeWorld& w) : w_(w) {}
  int refuse_after = -1;  ///< refuse every move after this many (-1: never)
  int moves = 0;
  bool move_relative(double dx, double dy, double dtheta) override {
    if (refuse_after >= 0 && moves >= refuse_after) return false;
    ++moves;
    const double c = std::cos(w_.heading);
    const double s = std::sin(w_.heading);
    w_.tool += Vector2d(c * dx - s * dy, s * dx + c * dy);
    w_.heading += dtheta;
    w_.note();
    return true;
  }

 private:
  FakeWorld& w_;
};

class Recorder final : public q::NavigationObserver {
 public:
  std::vector<q::LandmarkId> ids;
  std::vector<double> offset_errors;  ///< |claimed offset - true offset|, mm
  explicit Recorder(const FakeWorld& w) : w_(w) {}
  void landmark_reached(q::LandmarkId id, const Vector2d& offset) override {
    ids.push_back(id);
    const double c = std::cos(w_.heading);
    const double s = std::sin(w_.heading);
    const Vector2d world = w_.tool + Vector2d(c * offset.x() - s * offset.y(), s * offset.x() + c * offset.y());
    offset_errors.push_back((world - w_.landmarks[id]).norm());
  }

 private:
  const FakeWorld& w_;
};

// Spec §8's example, scaled to millimetres (25 mm a unit): RNG {0-2, 1-2, 1-3, 1-4}.
std::vector<Vector2d> example() {
  const std::vector<Vector2d> units{{0, 0}, {4, 0.5}, {1.5, 1.2}, {9, -1}, {6, 4.3}};
  std::vector<Vector2d> mm;
  mm.reserve(units.size());
  for (const Vector2d& p : units) mm.emplace_back(25 * p);
  return mm;
}

// A map of `landmarks` from exact panoramas at a few positions around them, each at another heading.
q::RelationalMap map_of(const std::vector<Vector2d>& landmarks) {
  q::RelationalMap map;
  FakeWorld w{landmarks};
  FakeEye eye(w);
  const std::vector<Vector2d> spots{{-20, -30}, {100, 60}, {200, 40}, {60, -40}, {170, 120}, {20, 80}};
  for (std::size_t i = 0; i < spots.size(); ++i) {
    w.tool = spots[i];
    w.heading = 0.7 * static_cast<double>(i);
    (void)q::observe(map, q::landmark_sightings(eye.look()));
  }
  return map;
}

TEST(QrmNavigator, FollowsTheSpecExampleRouteZeroTwoOneThree) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  std::vector<std::pair<q::LandmarkId, q::LandmarkId>> edges;
  for (const q::RngEdge& e : q::estimate_rng(map).edges) edges.emplace_back(e.i, e.j);
  ASSERT_EQ(edges, (std::vector<std::pair<q::LandmarkId, q::LandmarkId>>{{0, 2}, {1, 2}, {1, 3}, {1, 4}}));

  w.tool = {-15, -5};  // in 0's cell, clear of it
  w.heading = 2.0;     // the sensor's zero direction is nobody's business
  w.note();
  FakeEye eye(w);
  FakeArm arm(w);
  Recorder seen(w);
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, {}, &seen);
  EXPECT_EQ(r.ending, q::NavigationEnding::arrived) << r.reason;
  EXPECT_EQ(r.reached, (std::vector<q::LandmarkId>{0, 2, 1, 3}));
  EXPECT_EQ(r.first_route, (std::vector<q::LandmarkId>{0, 2, 1, 3}));
  EXPECT_EQ(seen.ids, r.reached);
  for (const double e : seen.offset_errors) EXPECT_LT(e, 1e-6);
  EXPECT_EQ(r.reroutes, 0);
  EXPECT_EQ(r.steps, arm.moves);
  EXPECT_EQ(r.frames, r.steps + 1);
  EXPECT_EQ(r.images_fused, 1 + r.steps / 10);
  // At the end the goal is the nearest landmark, and the tool kept 10 mm from every marble's surface.
  for (std::size_t i = 0; i + 1 < w.landmarks.size(); ++i) {
    EXPECT_LE((w.landmarks[3] - w.tool).norm(), (w.landmarks[i] - w.tool).norm());
  }
  EXPECT_GE(w.least_gap, 12.5);
  // Steps of δ: 5 mm each.
  for (std::size_t i = 1; i < w.track.size(); ++i) EXPECT_NEAR((w.track[i] - w.track[i - 1]).norm(), 5, 1e-9);
}

TEST(QrmNavigator, LeavingThePlannedRouteIsAReroute) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, -5};
  FakeEye eye(w);
  FakeArm arm(w);
  const std::vector<q::LandmarkId> planned{0, 4, 3};  // not the map's route
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, {}, nullptr, planned);
  EXPECT_EQ(r.ending, q::NavigationEnding::arrived) << r.reason;
  EXPECT_EQ(r.reroutes, 1);
  FakeWorld w2{example()};
  w2.tool = {-15, -5};
  FakeEye eye2(w2);
  FakeArm arm2(w2);
  q::RelationalMap map2 = map_of(w2.landmarks);
  const std::vector<q::LandmarkId> right{0, 2, 1, 3};
  EXPECT_EQ(q::navigate(map2, 3, eye2, arm2, {}, nullptr, right).reroutes, 0);
}

TEST(QrmNavigator, GoesRoundAMarbleInTheWayKeepingClear) {
  // The tool starts behind 0 as seen from 1: the straight way to 1 runs through 0.
  FakeWorld w{{{0, 0}, {120, 0}, {60, 90}}};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, 0};
  w.note();
  FakeEye eye(w);
  FakeArm arm(w);
  const q::NavigationReport r = q::navigate(map, 1, eye, arm, {});
  EXPECT_EQ(r.ending, q::NavigationEnding::arrived) << r.reason;
  EXPECT_EQ(r.reached, (std::vector<q::LandmarkId>{0, 1}));
  EXPECT_GT(r.detours, 0);
  EXPECT_GE(w.least_gap, 12.5);
}

TEST(QrmNavigator, ThroughAGapTooNarrowItGoesAround) {
  // 0 and 2 are 20 mm apart: the gap between them is narrower than twice the clearance, and the
  // tool starts on the far side of it from 1.
  FakeWorld w{{{0, 0}, {150, 10}, {0, 20}, {-60, 120}}};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, 10};
  w.note();
  FakeEye eye(w);
  FakeArm arm(w);
  const q::NavigationReport r = q::navigate(map, 1, eye, arm, {});
  EXPECT_EQ(r.ending, q::NavigationEnding::arrived) << r.reason;
  EXPECT_GE(w.least_gap, 12.5);
  EXPECT_LT(r.steps, 80);
}

TEST(QrmNavigator, NoPathWhenTheMapDoesNotHoldTheGoal) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, -5};
  FakeEye eye(w);
  FakeArm arm(w);
  const q::NavigationReport r = q::navigate(map, 7, eye, arm, {});
  EXPECT_EQ(r.ending, q::NavigationEnding::no_path);
  EXPECT_EQ(r.steps, 0);
  EXPECT_NE(r.reason.find("no path"), std::string::npos) << r.reason;
}

TEST(QrmNavigator, TargetLostWhenTheNextLandmarkNeverShows) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, -5};
  FakeEye eye(w);
  eye.hidden = {2};
  FakeArm arm(w);
  q::NavigatorConfig config;
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, config);
  EXPECT_EQ(r.ending, q::NavigationEnding::target_lost);
  EXPECT_NE(r.reason.find("landmark 2"), std::string::npos) << r.reason;
  // It looked round the marble it stood by first, as long as allowed.
  EXPECT_EQ(r.searches, config.search_steps);
}

TEST(QrmNavigator, StepLimit) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, -5};
  FakeEye eye(w);
  FakeArm arm(w);
  q::NavigatorConfig config;
  config.max_steps = 5;
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, config);
  EXPECT_EQ(r.ending, q::NavigationEnding::step_limit);
  EXPECT_EQ(r.steps, 5);
}

TEST(QrmNavigator, ARefusedMoveBlocksIt) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {-15, -5};
  FakeEye eye(w);
  FakeArm arm(w);
  arm.refuse_after = 2;
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, {});
  EXPECT_EQ(r.ending, q::NavigationEnding::blocked);
  EXPECT_EQ(r.steps, 2);
}

TEST(QrmNavigator, AtTheGoalAlreadyItArrivesWithoutMoving) {
  FakeWorld w{example()};
  q::RelationalMap map = map_of(w.landmarks);
  w.tool = {240, -25};  // nearest 3
  FakeEye eye(w);
  FakeArm arm(w);
  const q::NavigationReport r = q::navigate(map, 3, eye, arm, {});
  EXPECT_EQ(r.ending, q::NavigationEnding::arrived);
  EXPECT_EQ(r.steps, 0);
  EXPECT_EQ(r.reached, (std::vector<q::LandmarkId>{3}));
}

TEST(QrmLocalPath, StepsIntoTheTargetsCellRoundAnObstacle) {
  const std::vector<q::Obstacle> obstacles{{0, {15, 0}}, {1, {100, 0}}};
  const auto step = q::path_step(obstacles, 1, {100, 0}, 5, 14);
  ASSERT_TRUE(step.has_value());
  EXPECT_NEAR(step->norm(), 5, 1e-9);
  EXPECT_TRUE(q::step_allowed(obstacles, *step, 14));
  EXPECT_GT(std::abs(step->y()), 1);  // not straight through marble 0
  EXPECT_GT(step->x(), 0);
  // Walled in: no way out.
  std::vector<q::Obstacle> wall;
  for (int a = 0; a < 360; a += 20) {
    wall.push_back({static_cast<q::LandmarkId>(a / 20), 20 * Vector2d(std::cos(a * kDegree), std::sin(a * kDegree))});
  }
  wall.push_back({100, {200, 0}});
  EXPECT_FALSE(q::path_step(wall, 100, {200, 0}, 5, 14).has_value());
}

TEST(QrmNavigator, EndingNames) {
  EXPECT_EQ(q::navigation_ending_name(q::NavigationEnding::arrived), "arrived");
  EXPECT_EQ(q::navigation_ending_name(q::NavigationEnding::no_path), "no_path");
  EXPECT_EQ(q::navigation_ending_name(q::NavigationEnding::target_lost), "target_lost");
  EXPECT_EQ(q::navigation_ending_name(q::NavigationEnding::step_limit), "step_limit");
  EXPECT_EQ(q::navigation_ending_name(q::NavigationEnding::blocked), "blocked");
}

}  // namespace
