// The parts of Qualnav's navigator that need no rig: the hill-climb's cost and gradient against a
// numerical derivative, ranges by parallax against the geometry, and the clearance rule of moves.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "nav/qualnav/metric/viewframe.hpp"
#include "nav/qualnav/navigator/hill_climb.hpp"
#include "nav/qualnav/navigator/motion.hpp"
#include "nav/qualnav/navigator/orientation_heading.hpp"

namespace {

namespace q = neopipe::nav::qualnav;
using Eigen::Vector2d;

const std::vector<Vector2d> kMarks = {{0, 0}, {120, 10}, {150, 140}, {-20, 110}};

q::Viewframe seen_from(const Vector2d& p, double factor = 1.0) {
  std::vector<q::ViewedLandmark> v;
  for (std::size_t i = 0; i < kMarks.size(); ++i) {
    const Vector2d d = kMarks[i] - p;
    const double r = d.norm();
    v.push_back({i, std::atan2(d.y(), d.x()), 0.0035, r, r / factor, r * factor});
  }
  return q::make_viewframe(v, 0);
}

TEST(HillClimb, GradientMatchesANumericalDerivative) {
  const q::Viewframe goal = seen_from({60, 60});
  const Vector2d p(80, 45);
  const auto s = q::climb_state(seen_from(p), goal);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->pairs, 3);
  constexpr double h = 1e-4;
  const double jx = (q::climb_state(seen_from(p + Vector2d(h, 0)), goal)->cost -
                     q::climb_state(seen_from(p - Vector2d(h, 0)), goal)->cost) /
                    (2 * h);
  const double jy = (q::climb_state(seen_from(p + Vector2d(0, h)), goal)->cost -
                     q::climb_state(seen_from(p - Vector2d(0, h)), goal)->cost) /
                    (2 * h);
  EXPECT_NEAR(s->gradient.x(), jx, 1e-6 + 1e-3 * std::abs(jx));
  EXPECT_NEAR(s->gradient.y(), jy, 1e-6 + 1e-3 * std::abs(jy));
}

TEST(HillClimb, FiveMillimetreStepsReachTheGoalView) {
  const Vector2d goal_at(60, 60);
  const q::Viewframe goal = seen_from(goal_at);
  Vector2d p(95, 30);
  q::HillClimbSettings settings;
  for (int step = 0; step < 40; ++step) {
    const auto s = q::climb_state(seen_from(p, 1.5), goal);
    ASSERT_TRUE(s.has_value());
    if (s->worst_error < settings.done_error) break;
    p += q::climb_step(*s, settings) * std::min(1.0, std::sqrt(s->cost) * 20);  // shorter near the end
  }
  EXPECT_LT((p - goal_at).norm(), 3.0) << p.transpose();
}

TEST(Parallax, RecoversTheRange) {
  const Vector2d landmark(14, 9);
  const Vector2d move(-2, 5);
  const double b0 = std::atan2(landmark.y(), landmark.x());
  const Vector2d from_there = landmark - move;
  const double b1 = std::atan2(from_there.y(), from_there.x());
  const auto r = q::parallax_range(b0, move, b1);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, from_there.norm(), 1e-9);
  EXPECT_FALSE(q::parallax_range(b0, Vector2d(0, 0), b0).has_value());
}

TEST(SafeMove, KeepsTheClearanceOfEveryPossiblePosition) {
  // A marble 20 mm straight ahead, its range known within [16, 26]: a 10 mm step ahead would come
  // within 6-16 mm of it; the move taken turns away and keeps r_m + 10 + 1.5 from the whole segment.
  q::Viewframe v = q::make_viewframe({{0, 0.0, 0.0035, 20, 16, 26}}, 0);
  const q::ClearanceRule rule;
  const auto m = q::safe_move(v, 0.0, 10, rule);
  ASSERT_TRUE(m.has_value());
  EXPECT_GT(std::abs(std::atan2(m->y(), m->x())), 0.1);
  EXPECT_GE(q::track_gap(v.landmarks[0], *m), std::min(rule.required(), q::current_gap(v.landmarks[0])) - 1e-9);
  // Nothing in the way: straight ahead.
  const auto free = q::safe_move(q::make_viewframe({{0, std::numbers::pi, 0.0035, 200, 100, 300}}, 0), 0.0, 10, rule);
  ASSERT_TRUE(free.has_value());
  EXPECT_NEAR(free->x(), 10, 1e-9);
  EXPECT_NEAR(free->y(), 0, 1e-9);
}

// P (−10, 100) left of Q (10, 100) seen from the origin: b heads between them, l passes beyond P,
// r beyond Q, a at P; whatever the tool's heading.
TEST(OrientationHeading, ControlLawsOfTheDecision) {
  constexpr double kDeg = std::numbers::pi / 180;
  for (const double heading : {0.0, 1.0, -2.5}) {
    std::vector<q::ViewedLandmark> v;
    for (const auto& [id, at] : {std::pair<q::LandmarkId, Vector2d>{7, {-10, 100}}, {9, {10, 100}}}) {
      v.push_back({id, std::atan2(at.y(), at.x()) - heading, 0.0035, at.norm(), at.norm(), at.norm()});
    }
    const q::Viewframe view = q::make_viewframe(v, heading);
    const auto world = [&](q::OrientationKind k) {
      return q::wrap_angle(*q::orientation_heading(k, 7, 9, view) + heading);
    };
    const double p = std::atan2(100.0, -10.0);
    const double qq = std::atan2(100.0, 10.0);
    EXPECT_NEAR(world(q::OrientationKind::b), 90 * kDeg, 1e-9);
    EXPECT_NEAR(world(q::OrientationKind::l), p + 10 * kDeg, 1e-9);
    EXPECT_NEAR(world(q::OrientationKind::r), qq - 10 * kDeg, 1e-9);
    EXPECT_NEAR(world(q::OrientationKind::a), p, 1e-9);
    // l crosses the LPB's line y = 100 beyond P (x < −10), r beyond Q (x > 10), b between.
    EXPECT_LT(100 / std::tan(world(q::OrientationKind::l)), -10);
    EXPECT_GT(100 / std::tan(world(q::OrientationKind::r)), 10);
    EXPECT_FALSE(q::orientation_heading(q::OrientationKind::b, 7, 8, view).has_value());
  }
}

}  // namespace
