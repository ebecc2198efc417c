#pragma once
// SCARA kinematics: two revolute joints in the horizontal plane (shoulder, elbow) place the tool
// axis at (x, y); a roll joint turns the tool frame; the height is fixed and not modelled.
//
//   elbow = base + l1 (cos q1, sin q1)
//   tool  = elbow + l2 (cos(q1 + q2), sin(q1 + q2)),   tool heading theta = q1 + q2 + q3
//
// Angles are radians, counter-clockwise, the shoulder angle measured from the world's East. Every
// position is solved in one elbow configuration (the sign of q2), so the arm never flips its elbow
// between two nearby targets.

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <variant>

#include "sim/arm/angles.hpp"
#include "sim/pose2.hpp"

namespace neopipe::sim {

/// A pose the arm cannot take; the message says which reach or joint limit fails, with the numbers.
class ReachError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JointAngles {
  double shoulder = 0;  ///< q1, rad, from East
  double elbow = 0;     ///< q2, rad, relative to the upper arm
  double roll = 0;      ///< q3, rad, relative to the forearm
};

struct JointLimits {
  double min = 0;  ///< rad
  double max = 0;  ///< rad
};

/// Which way the elbow bends. Positive: q2 > 0, the forearm turns counter-clockwise from the upper
/// arm, and seen from the base the elbow lies to the right of the line to the tool.
enum class ElbowBend { positive, negative };

/// The defaults suit the default 500 x 500 mm workspace: they are what scara_for_workspace({500,
/// 500}) returns, and they reach every point of [-25, 525]^2 with any tool heading.
struct ScaraGeometry {
  Eigen::Vector2d base{250, -125};  ///< mm, the shoulder axis: centred below the workspace's South edge
  double l1 = 375;                  ///< mm, shoulder axis to elbow axis
  double l2 = 375;                  ///< mm, elbow axis to tool axis
  JointLimits shoulder{radians(-90), radians(180)};
  /// Signed; the bend picks the part on its side of 0. The small end keeps the arm off the stretched
  /// singularity, the large end keeps the forearm from folding onto the upper arm.
  JointLimits elbow{radians(1), radians(170)};
  /// A full turn (or more) lets the tool take any heading anywhere; the navigator can turn freely.
  JointLimits roll{radians(-180), radians(180)};
  ElbowBend bend = ElbowBend::positive;
};

/// The kinematics of one validated geometry.
class Scara {
 public:
  /// Throws std::invalid_argument naming the field when the geometry is not a usable arm (lengths
  /// not positive, a limit range empty or not finite, no elbow angle on the side of `bend`).
  explicit Scara(ScaraGeometry geometry);

  const ScaraGeometry& geometry() const { return geometry_; }
  /// Distances from the base the tool axis can reach within the elbow limits, mm.
  double min_reach() const { return min_reach_; }
  double max_reach() const { return max_reach_; }

  /// The tool pose for joint angles (not checked against the limits). theta is not wrapped.
  Pose2 forward(const JointAngles& q) const;
  /// Where the elbow axis is for joint angles, mm.
  Eigen::Vector2d elbow_position(const JointAngles& q) const;

  /// The joint angles that put the tool at `tool` (heading taken modulo 2 pi; each angle is the
  /// representative within its limits, nearest the middle of the range when there are several).
  /// Throws ReachError when the position is out of reach or needs a joint beyond its limits.
  JointAngles inverse(const Pose2& tool) const;
  /// Whether inverse(tool) would succeed.
  bool reachable(const Pose2& tool) const;

 private:
  std::variant<JointAngles, std::string> solve(const Pose2& tool) const;

  ScaraGeometry geometry_;
  double elbow_lo_ = 0;  ///< |q2| range on the side of the bend, rad
  double elbow_hi_ = 0;
  double min_reach_ = 0;
  double max_reach_ = 0;
};

}  // namespace neopipe::sim
