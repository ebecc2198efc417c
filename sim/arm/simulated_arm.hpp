#pragma once
// The simulated SCARA arm the navigator drives: relative moves in the tool frame, with motion errors.

#include <cstdint>

#include "sim/arm/motion_model.hpp"
#include "sim/arm/scara.hpp"
#include "sim/pose2.hpp"
#include "sim/random.hpp"

namespace neopipe::sim {

/// Holds the ground truth (the pose the tool really has) beside the commanded pose (where the
/// commands alone would have put it: dead reckoning from the start), so that tests and reports can
/// compare them. Only relative moves carry errors. The same geometry, errors, seed, start and
/// commands give bit-identical poses.
class SimulatedArm {
 public:
  /// Throws std::invalid_argument for an unusable geometry or error model, ReachError when `start`
  /// is out of reach.
  SimulatedArm(const ScaraGeometry& geometry, const MotionErrors& errors, std::uint64_t seed, const Pose2& start);

  /// Moves by (dx, dy) mm in the current tool frame and then turns by dtheta rad, as commanded, but
  /// really by perturb(errors, command). When the pose really reached would be out of reach, throws
  /// ReachError and changes nothing, the random stream included (the same command fails again the
  /// same way). Throws std::invalid_argument for a command that is not finite.
  void move_relative(double dx, double dy, double dtheta);

  /// Places the tool exactly at `pose`, without errors, and makes it the commanded pose too: for
  /// setting up a run, not for the navigator. Throws ReachError, changing nothing, when out of reach.
  void move_to(const Pose2& pose);

  const Pose2& pose() const { return pose_; }  ///< ground truth
  const Pose2& commanded_pose() const { return commanded_; }
  const JointAngles& joints() const { return joints_; }  ///< of pose()
  const Scara& kinematics() const { return scara_; }
  const MotionErrors& errors() const { return errors_; }

 private:
  Scara scara_;
  MotionErrors errors_;
  Random random_;
  Pose2 pose_;
  Pose2 commanded_;
  JointAngles joints_;
};

}  // namespace neopipe::sim
