// SimulatedArm: determinism (same seed -> bit-identical poses, different seed -> different), zero
// errors -> exactly the compose() poses, heading drift carried into later moves, refused moves
// leaving no trace, exact placement, and joint angles that match the ground truth.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sim/arm/simulated_arm.hpp"

namespace neopipe::sim {
namespace {

constexpr double kPi = std::numbers::pi;
const Pose2 kCentre{250, 250, 0};

/// A command stream that wanders about the workspace without leaving it: each move heads halfway
/// back to the centre (as the arm believes it is: the commanded pose) plus up to 40 mm of jitter,
/// with a turn of up to 30 deg either way.
ToolMove next_command(const SimulatedArm& arm, Random& commands) {
  const Pose2& c = arm.commanded_pose();
  const double wx = (kCentre.x - c.x) / 2 + commands.uniform(-40, 40);
  const double wy = (kCentre.y - c.y) / 2 + commands.uniform(-40, 40);
  return {std::cos(c.theta) * wx + std::sin(c.theta) * wy, -std::sin(c.theta) * wx + std::cos(c.theta) * wy,
          commands.uniform(-kPi / 6, kPi / 6)};
}

std::vector<Pose2> run(std::uint64_t seed, const MotionErrors& errors, int moves) {
  SimulatedArm arm(ScaraGeometry{}, errors, seed, kCentre);
  Random commands(77);
  std::vector<Pose2> poses;
  for (int i = 0; i < moves; ++i) {
    const ToolMove m = next_command(arm, commands);
    arm.move_relative(m.dx, m.dy, m.dtheta);
    poses.push_back(arm.pose());
  }
  return poses;
}

bool identical(const Pose2& a, const Pose2& b) {
  return a.x == b.x && a.y == b.y && a.theta == b.theta;
}

TEST(SimulatedArm, SameSeedGivesBitIdenticalPoses) {
  const auto a = run(42, MotionErrors{}, 2000);
  const auto b = run(42, MotionErrors{}, 2000);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_TRUE(identical(a[i], b[i])) << "move " << i;
}

TEST(SimulatedArm, DifferentSeedsGiveDifferentErrorsFromTheFirstMove) {
  const auto a = run(42, MotionErrors{}, 100);
  const auto b = run(43, MotionErrors{}, 100);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_FALSE(identical(a[i], b[i])) << "move " << i;
}

TEST(SimulatedArm, ZeroErrorsFollowComposeExactly) {
  SimulatedArm arm(ScaraGeometry{}, MotionErrors::none(), 1, kCentre);
  Random commands(8);
  Pose2 expected = kCentre;
  for (int i = 0; i < 1000; ++i) {
    const ToolMove m = next_command(arm, commands);
    arm.move_relative(m.dx, m.dy, m.dtheta);
    expected = compose(expected, m.dx, m.dy, m.dtheta);
    ASSERT_TRUE(identical(arm.pose(), expected)) << "move " << i;
    ASSERT_TRUE(identical(arm.commanded_pose(), expected)) << "move " << i;
  }
}

TEST(SimulatedArm, ErrorsMakeTheTruthDriftFromTheCommandedPose) {
  SimulatedArm arm(ScaraGeometry{}, MotionErrors{}, 5, kCentre);
  Random commands(9);
  for (int i = 0; i < 50; ++i) {
    const ToolMove m = next_command(arm, commands);
    arm.move_relative(m.dx, m.dy, m.dtheta);
  }
  const double drift = std::hypot(arm.pose().x - arm.commanded_pose().x, arm.pose().y - arm.commanded_pose().y);
  EXPECT_GT(drift, 0.01);  // 50 moves of ~40 mm at 0.17 mm sigma each: a drift of about a millimetre
  EXPECT_LT(drift, 20);
  EXPECT_NE(arm.pose().theta, arm.commanded_pose().theta);
}

TEST(SimulatedArm, AHeadingErrorTurnsEveryLaterMove) {
  MotionErrors heading_only = MotionErrors::none();
  heading_only.rotation_sigma0 = radians(2);
  SimulatedArm arm(ScaraGeometry{}, heading_only, 3, kCentre);
  arm.move_relative(0, 0, 0);  // stands still, but the tool frame turns by the heading error
  const Pose2 turned = arm.pose();
  EXPECT_EQ(turned.x, kCentre.x);
  EXPECT_EQ(turned.y, kCentre.y);
  EXPECT_NE(turned.theta, 0);
  arm.move_relative(100, 0, 0);  // exact translation, but along the turned x axis
  EXPECT_EQ(arm.pose().x, turned.x + 100 * std::cos(turned.theta));
  EXPECT_EQ(arm.pose().y, turned.y + 100 * std::sin(turned.theta));
  EXPECT_EQ(arm.commanded_pose().y, kCentre.y);
}

TEST(SimulatedArm, AnUnreachableMoveIsRefusedAndLeavesNoTrace) {
  SimulatedArm arm(ScaraGeometry{}, MotionErrors{}, 21, kCentre);
  SimulatedArm twin(ScaraGeometry{}, MotionErrors{}, 21, kCentre);
  arm.move_relative(10, 5, 0.1);
  twin.move_relative(10, 5, 0.1);
  const Pose2 before = arm.pose();
  const Pose2 commanded_before = arm.commanded_pose();
  const JointAngles joints_before = arm.joints();
  try {
    arm.move_relative(1000, 0, 0);
    FAIL() << "a 1 m move from the centre was accepted";
  } catch (const ReachError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("move (1000.00, 0.00, 0.00 deg) from ("), std::string::npos) << m;
    EXPECT_NE(m.find("mm from the base (250.00, -125.00); the arm reaches 65.37..749.97 mm"), std::string::npos) << m;
  }
  EXPECT_TRUE(identical(arm.pose(), before));
  EXPECT_TRUE(identical(arm.commanded_pose(), commanded_before));
  EXPECT_EQ(arm.joints().shoulder, joints_before.shoulder);
  EXPECT_EQ(arm.joints().elbow, joints_before.elbow);
  EXPECT_EQ(arm.joints().roll, joints_before.roll);
  // The refused move drew nothing: the next move matches the twin's, which never tried it.
  arm.move_relative(-20, 15, -0.2);
  twin.move_relative(-20, 15, -0.2);
  EXPECT_TRUE(identical(arm.pose(), twin.pose()));
}

TEST(SimulatedArm, MoveToPlacesExactlyAndRestartsTheCommandedPose) {
  SimulatedArm arm(ScaraGeometry{}, MotionErrors{}, 2, kCentre);
  arm.move_relative(50, 0, 0.3);
  const Pose2 target{100, 400, -2.5};
  arm.move_to(target);
  EXPECT_TRUE(identical(arm.pose(), target));
  EXPECT_TRUE(identical(arm.commanded_pose(), target));
  EXPECT_THROW(arm.move_to({250, 900, 0}), ReachError);
  EXPECT_TRUE(identical(arm.pose(), target));
}

TEST(SimulatedArm, JointAnglesAreThoseOfTheTruePose) {
  SimulatedArm arm(ScaraGeometry{}, MotionErrors{}, 4, kCentre);
  Random commands(10);
  for (int i = 0; i < 200; ++i) {
    const ToolMove m = next_command(arm, commands);
    arm.move_relative(m.dx, m.dy, m.dtheta);
    const Pose2 fk = arm.kinematics().forward(arm.joints());
    ASSERT_NEAR(fk.x, arm.pose().x, 1e-9);
    ASSERT_NEAR(fk.y, arm.pose().y, 1e-9);
    ASSERT_NEAR(wrap_pi(fk.theta - arm.pose().theta), 0, 1e-12);
    ASSERT_GT(arm.joints().elbow, 0);
  }
}

TEST(SimulatedArm, AnUnreachableStartOrANonFiniteCommandIsRejected) {
  EXPECT_THROW(SimulatedArm(ScaraGeometry{}, MotionErrors{}, 1, {250, 700, 0}), ReachError);
  SimulatedArm arm(ScaraGeometry{}, MotionErrors{}, 1, kCentre);
  EXPECT_THROW(arm.move_relative(std::nan(""), 0, 0), std::invalid_argument);
  EXPECT_THROW(arm.move_relative(0, 0, INFINITY), std::invalid_argument);
  EXPECT_TRUE(identical(arm.pose(), kCentre));
}

}  // namespace
}  // namespace neopipe::sim
