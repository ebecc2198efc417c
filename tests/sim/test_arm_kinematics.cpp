// SCARA kinematics: joint angles of 0, 45 and 90 deg give the poses worked out by hand (two
// geometries, both elbow bends), FK(IK(p)) = p over the workspace (grid and random poses), IK(FK(q)) = q within
// the limits, one elbow configuration everywhere, unreachable poses rejected with messages that
// name the numbers, geometry validation, and the workspace sizing rule for several workspaces.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "sim/arm/scara.hpp"
#include "sim/arm/scara_sizing.hpp"
#include "sim/random.hpp"

namespace neopipe::sim {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kPositionTolerance = 1e-9;  // mm
constexpr double kHeadingTolerance = 1e-12;  // rad

struct RoundTripError {
  double position = 0;  ///< largest |FK(IK(p)) - p|, mm
  double heading = 0;   ///< largest wrapped heading difference, rad
  int wrong_elbow = 0;  ///< solutions whose elbow angle has the wrong sign
};

/// FK(IK(p)) against p for every point of an n x n grid over [x0, x1] x [y0, y1], with headings that
/// sweep several turns (so both wrapping and the roll range are exercised). Fails on any rejection.
RoundTripError sweep_grid(const Scara& arm, double x0, double x1, double y0, double y1, int n) {
  RoundTripError worst;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double t = static_cast<double>(i * n + j) / (n * n);
      const Pose2 p{x0 + (x1 - x0) * i / (n - 1), y0 + (y1 - y0) * j / (n - 1), -3 * kPi + 6 * kPi * t};
      try {
        const JointAngles q = arm.inverse(p);
        const Pose2 back = arm.forward(q);
        worst.position = std::max(worst.position, std::hypot(back.x - p.x, back.y - p.y));
        worst.heading = std::max(worst.heading, std::abs(wrap_pi(back.theta - p.theta)));
        if ((arm.geometry().bend == ElbowBend::positive) != (q.elbow > 0)) ++worst.wrong_elbow;
      } catch (const ReachError& e) {
        ADD_FAILURE() << "grid point rejected: " << e.what();
        return worst;
      }
    }
  }
  return worst;
}

std::string reach_message(const Scara& arm, const Pose2& p) {
  try {
    arm.inverse(p);
  } catch (const ReachError& e) {
    EXPECT_FALSE(arm.reachable(p));
    return e.what();
  }
  ADD_FAILURE() << "pose (" << p.x << ", " << p.y << ", " << p.theta << ") was not rejected";
  return {};
}

TEST(ArmKinematics, DefaultGeometryIsTheOneSizedForTheDefaultWorkspace) {
  const ScaraGeometry sized = scara_for_workspace({500, 500});
  const ScaraGeometry defaults;
  EXPECT_EQ(sized.base, defaults.base);
  EXPECT_EQ(sized.l1, defaults.l1);
  EXPECT_EQ(sized.l2, defaults.l2);
  EXPECT_EQ(defaults.base, Eigen::Vector2d(250, -125));
  EXPECT_EQ(defaults.l1, 375);
  EXPECT_EQ(defaults.l2, 375);
  const Scara arm(defaults);
  EXPECT_NEAR(arm.max_reach(), 750 * std::cos(radians(0.5)), 1e-12);
  EXPECT_NEAR(arm.min_reach(), 750 * std::cos(radians(85)), 1e-12);
}

// Absolute poses worked out by hand from the model in scara.hpp (elbow = base + l1 (cos q1, sin q1),
// tool = elbow + l2 (cos(q1 + q2), sin(q1 + q2)), heading q1 + q2 + q3), for joint angles whose sines
// and cosines are 0, +-1 or sqrt(2)/2. The round trips above hold for any self-consistent pair of FK
// and IK (links swapped in both, a heading offset in both, a mirrored arm); these do not.
struct KnownPose {
  JointAngles q;  ///< degrees here, converted below
  Eigen::Vector2d elbow;
  Pose2 tool;          ///< theta in degrees
  bool within_limits;  ///< IK must give q back
};

void expect_known_poses(const ScaraGeometry& g, const std::vector<KnownPose>& poses) {
  const Scara arm(g);
  for (const KnownPose& k : poses) {
    const JointAngles q{radians(k.q.shoulder), radians(k.q.elbow), radians(k.q.roll)};
    SCOPED_TRACE(testing::Message() << "q = (" << k.q.shoulder << ", " << k.q.elbow << ", " << k.q.roll << ") deg");
    const Pose2 p = arm.forward(q);
    EXPECT_NEAR(p.x, k.tool.x, kPositionTolerance);
    EXPECT_NEAR(p.y, k.tool.y, kPositionTolerance);
    EXPECT_NEAR(p.theta, radians(k.tool.theta), kHeadingTolerance);
    const Eigen::Vector2d e = arm.elbow_position(q);
    EXPECT_NEAR(e.x(), k.elbow.x(), kPositionTolerance);
    EXPECT_NEAR(e.y(), k.elbow.y(), kPositionTolerance);
    if (!k.within_limits) continue;
    const JointAngles back = arm.inverse({k.tool.x, k.tool.y, radians(k.tool.theta)});
    EXPECT_NEAR(back.shoulder, q.shoulder, 1e-12);
    EXPECT_NEAR(back.elbow, q.elbow, 1e-12);
    EXPECT_NEAR(back.roll, q.roll, 1e-12);
  }
}

TEST(ArmKinematics, KnownJointAnglesGiveTheHandComputedPoses) {
  // The default arm: base (250, -125), both links 375 mm.
  const double h = 375 * std::numbers::sqrt2 / 2;  // 265.165... mm, a link at 45 deg
  expect_known_poses(
      ScaraGeometry{},
      {
          {{0, 0, 0}, {625, -125}, {1000, -125, 0}, false},                    // stretched East (elbow below its limit)
          {{90, 0, 0}, {250, 250}, {250, 625, 90}, false},                     // stretched North
          {{0, 90, 0}, {625, -125}, {625, 250, 90}, true},                     // upper arm East, forearm North
          {{90, 90, 0}, {250, 250}, {-125, 250, 180}, true},                   // upper arm North, forearm West
          {{90, 90, -90}, {250, 250}, {-125, 250, 90}, true},                  // the same, tool turned back to North
          {{45, 90, 0}, {250 + h, -125 + h}, {250, -125 + 2 * h, 135}, true},  // tool straight North of the base
          // At the shoulder's limits (IK there is a matter of rounding): forearm South, heading not
          // wrapped by FK; forearm East.
          {{180, 90, 45}, {-125, -125}, {-125, -500, 315}, false},
          {{-90, 90, 0}, {250, -500}, {625, -500, 0}, false},
      });
}

TEST(ArmKinematics, KnownJointAnglesGiveTheHandComputedPosesWithUnequalLinks) {
  // Unequal links tell l1 from l2: swapping them anywhere moves every pose below.
  ScaraGeometry g;
  g.base = {100, -50};
  g.l1 = 420;
  g.l2 = 310;
  expect_known_poses(g, {
                            {{0, 90, 0}, {520, -50}, {520, 260, 90}, true},
                            {{90, 90, 0}, {100, 370}, {-210, 370, 180}, true},
                            {{90, 90, 30}, {100, 370}, {-210, 370, 210}, true},
                            {{0, 0, 0}, {520, -50}, {830, -50, 0}, false},
                        });
  const double s = std::numbers::sqrt2 / 2;
  g.bend = ElbowBend::negative;  // the elbow to the other side: q2 = -90 deg
  g.elbow = {radians(-170), radians(-1)};
  expect_known_poses(g, {
                            {{90, -90, 0}, {100, 370}, {410, 370, 0}, true},
                            {{135, -90, 0}, {100 - 420 * s, -50 + 420 * s}, {100 - 110 * s, -50 + 730 * s, 45}, true},
                        });
}

TEST(ArmKinematics, EveryPointOfTheDefaultWorkspaceAndItsMarginRoundTripsOnAOneMillimetreGrid) {
  const Scara arm{ScaraGeometry{}};
  const RoundTripError e = sweep_grid(arm, -25, 525, -25, 525, 551);  // 303,601 poses, 1 mm apart
  EXPECT_LE(e.position, kPositionTolerance);
  EXPECT_LE(e.heading, kHeadingTolerance);
  EXPECT_EQ(e.wrong_elbow, 0);
  std::printf(
      "[ measured ] default arm, 1 mm grid over [-25, 525]^2: max |FK(IK(p)) - p| = %.3g mm, heading %.3g rad\n",
      e.position, e.heading);
}

TEST(ArmKinematics, RandomPosesRoundTrip) {
  const Scara arm{ScaraGeometry{}};
  Random random(11);
  double worst_position = 0;
  double worst_heading = 0;
  for (int i = 0; i < 200000; ++i) {
    const Pose2 p{random.uniform(-25, 525), random.uniform(-25, 525), random.uniform(-20 * kPi, 20 * kPi)};
    const Pose2 back = arm.forward(arm.inverse(p));
    worst_position = std::max(worst_position, std::hypot(back.x - p.x, back.y - p.y));
    worst_heading = std::max(worst_heading, std::abs(wrap_pi(back.theta - p.theta)));
  }
  EXPECT_LE(worst_position, kPositionTolerance);
  EXPECT_LE(worst_heading, kHeadingTolerance);
  std::printf("[ measured ] default arm, 200,000 random poses: max |FK(IK(p)) - p| = %.3g mm, heading %.3g rad\n",
              worst_position, worst_heading);
}

/// Random joint angles within the limits (the roll kept off the ends of its full turn, where the
/// heading alone cannot tell -180 from +180 deg) come back from IK(FK(q)).
void expect_joints_round_trip(const ScaraGeometry& g, std::uint64_t seed) {
  const Scara arm(g);
  Random random(seed);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    const JointAngles q{random.uniform(g.shoulder.min, g.shoulder.max), random.uniform(g.elbow.min, g.elbow.max),
                        random.uniform(g.roll.min + 1e-6, g.roll.max - 1e-6)};
    const JointAngles back = arm.inverse(arm.forward(q));
    worst = std::max(
        {worst, std::abs(back.shoulder - q.shoulder), std::abs(back.elbow - q.elbow), std::abs(back.roll - q.roll)});
  }
  EXPECT_LE(worst, 1e-12) << "largest joint angle difference, rad";
  std::printf("[ measured ] 100,000 joint angles within the limits: max |IK(FK(q)) - q| = %.3g rad\n", worst);
}

TEST(ArmKinematics, JointAnglesWithinTheLimitsRoundTrip) {
  expect_joints_round_trip(ScaraGeometry{}, 12);
}

TEST(ArmKinematics, JointAnglesRoundTripWithTheOtherElbowAndUnequalLinks) {
  ScaraGeometry g;
  g.l1 = 420;
  g.l2 = 310;
  g.bend = ElbowBend::negative;
  g.elbow = {radians(-165), radians(-3)};
  g.shoulder = {radians(-30), radians(210)};
  g.roll = {radians(-100), radians(250)};
  expect_joints_round_trip(g, 13);
}

TEST(ArmKinematics, PositiveBendPutsTheElbowRightOfTheLineFromBaseToTool) {
  for (const ElbowBend bend : {ElbowBend::positive, ElbowBend::negative}) {
    ScaraGeometry g;
    g.bend = bend;
    if (bend == ElbowBend::negative) g.elbow = {radians(-170), radians(-1)};
    const Scara arm(g);
    const Pose2 tool{100, 400, 0};
    const Eigen::Vector2d to_tool = Eigen::Vector2d(tool.x, tool.y) - g.base;
    const Eigen::Vector2d to_elbow = arm.elbow_position(arm.inverse(tool)) - g.base;
    const double cross = to_tool.x() * to_elbow.y() - to_tool.y() * to_elbow.x();  // > 0: elbow on the left
    EXPECT_EQ(cross < 0, bend == ElbowBend::positive);
  }
}

TEST(ArmKinematics, TheReachBoundaryItselfIsReachable) {
  const ScaraGeometry g;
  const Scara arm(g);
  EXPECT_TRUE(arm.reachable(arm.forward({radians(90), g.elbow.min, 0})));     // stretched as far as allowed
  EXPECT_TRUE(arm.reachable(arm.forward({radians(60), g.elbow.max, 0})));     // folded as far as allowed
  EXPECT_TRUE(arm.reachable(arm.forward({g.shoulder.min, radians(40), 0})));  // at both shoulder limits
  EXPECT_TRUE(arm.reachable(arm.forward({g.shoulder.max, radians(40), 0})));
}

TEST(ArmKinematics, TooFarIsRejectedWithTheDistanceAndTheReach) {
  const Scara arm{ScaraGeometry{}};
  const std::string m = reach_message(arm, {250, 700, 0});
  EXPECT_NE(m.find("pose (250.00, 700.00) is 825.00 mm from the base (250.00, -125.00)"), std::string::npos) << m;
  EXPECT_NE(m.find("the arm reaches 65.37..749.97 mm"), std::string::npos) << m;
}

TEST(ArmKinematics, TooNearIsRejectedWithTheDistanceAndTheReach) {
  const Scara arm{ScaraGeometry{}};
  const std::string m = reach_message(arm, {250, -100, 0});
  EXPECT_NE(m.find("is 25.00 mm from the base"), std::string::npos) << m;
  EXPECT_NE(m.find("the arm reaches 65.37..749.97 mm"), std::string::npos) << m;
}

TEST(ArmKinematics, WithinTheLinksButBeyondTheElbowLimitsIsRejected) {
  // 749.99 mm < l1 + l2 = 750 mm, and 30 mm > |l1 - l2| = 0: only the elbow limits (1..170 deg) forbid them.
  const Scara arm{ScaraGeometry{}};
  EXPECT_NE(reach_message(arm, {250, -125 + 749.99, 0}).find("is 749.99 mm from the base"), std::string::npos);
  EXPECT_NE(reach_message(arm, {250, -125 + 30, 0}).find("is 30.00 mm from the base"), std::string::npos);
}

TEST(ArmKinematics, BeyondTheShoulderLimitsIsRejectedWithTheAngleNeeded) {
  // Straight South of the base, 600 mm away: elbow 2 acos(0.8) = 73.74 deg, shoulder -90 - 36.87 deg.
  const Scara arm{ScaraGeometry{}};
  const std::string m = reach_message(arm, {250, -725, 0});
  EXPECT_NE(m.find("pose (250.00, -725.00) needs the shoulder at -126.87 deg (elbow 73.74 deg)"), std::string::npos)
      << m;
  EXPECT_NE(m.find("its limits are -90.00..180.00 deg"), std::string::npos) << m;
}

TEST(ArmKinematics, BeyondTheRollLimitsIsRejectedWithTheAngleNeeded) {
  ScaraGeometry g;
  g.roll = {radians(-90), radians(90)};
  const Scara arm(g);
  const JointAngles q{radians(30), radians(100), radians(0)};
  const Pose2 p = arm.forward(q);
  EXPECT_TRUE(arm.reachable({p.x, p.y, p.theta + radians(89)}));
  const std::string m = reach_message(arm, {p.x, p.y, p.theta + radians(135)});
  EXPECT_NE(m.find("heading 265.00 deg"), std::string::npos) << m;
  EXPECT_NE(m.find("needs the roll at 135.00 deg; its limits are -90.00..90.00 deg"), std::string::npos) << m;
}

TEST(ArmKinematics, NonFinitePosesAreRejected) {
  const Scara arm{ScaraGeometry{}};
  EXPECT_NE(reach_message(arm, {std::nan(""), 100, 0}).find("is not finite"), std::string::npos);
  EXPECT_NE(reach_message(arm, {100, 100, INFINITY}).find("is not finite"), std::string::npos);
}

TEST(ArmKinematics, UnusableGeometriesAreRejectedNamingTheField) {
  const auto message = [](const ScaraGeometry& g) {
    try {
      const Scara arm(g);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  ScaraGeometry g;
  g.l2 = 0;
  EXPECT_NE(message(g).find("link lengths"), std::string::npos);
  g = {};
  g.base.x() = std::nan("");
  EXPECT_NE(message(g).find("base"), std::string::npos);
  g = {};
  g.shoulder = {radians(10), radians(-10)};
  EXPECT_NE(message(g).find("shoulder limits 10.00..-10.00 deg"), std::string::npos) << message(g);
  g = {};
  g.bend = ElbowBend::negative;  // the default elbow limits hold positive angles only
  EXPECT_NE(message(g).find("elbow limits 1.00..170.00 deg allow no negative elbow angle"), std::string::npos)
      << message(g);
  g = {};
  g.elbow = {radians(1), radians(190)};
  EXPECT_NE(message(g).find("beyond -180..180"), std::string::npos) << message(g);
  g = {};
  g.roll.max = INFINITY;
  EXPECT_NE(message(g).find("roll limits"), std::string::npos) << message(g);
}

TEST(ArmKinematics, ArmsSizedForOtherWorkspacesReachAllOfThem) {
  for (const Eigen::Vector2d& size : {Eigen::Vector2d(100, 100), Eigen::Vector2d(1000, 200), Eigen::Vector2d(200, 1000),
                                      Eigen::Vector2d(37, 5000), Eigen::Vector2d(5000, 37), Eigen::Vector2d(1, 1)}) {
    SCOPED_TRACE(testing::Message() << "workspace " << size.x() << " x " << size.y());
    const Scara arm(scara_for_workspace(size));
    const double m = 0.05 * size.maxCoeff();
    const RoundTripError e = sweep_grid(arm, -m, size.x() + m, -m, size.y() + m, 201);
    EXPECT_LE(e.position, kPositionTolerance);
    EXPECT_LE(e.heading, kHeadingTolerance);
    EXPECT_EQ(e.wrong_elbow, 0);
  }
}

TEST(ArmKinematics, SizingRejectsAnEmptyWorkspace) {
  EXPECT_THROW(scara_for_workspace({0, 500}), std::invalid_argument);
  EXPECT_THROW(scara_for_workspace({500, -1}), std::invalid_argument);
  EXPECT_THROW(scara_for_workspace({std::nan(""), 500}), std::invalid_argument);
}

}  // namespace
}  // namespace neopipe::sim
