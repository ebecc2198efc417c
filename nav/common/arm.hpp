#pragma once
// The arm as every navigator commands it: relative moves in its own tool frame, nothing else. No
// navigator can ask where the arm is; it finds out by looking. The rig (rig/station.hpp) puts the
// simulated SCARA arm, with its motion errors, behind this interface.

namespace neopipe::nav {

class Arm {
 public:
  virtual ~Arm() = default;
  /// Moves the tool by (dx, dy) mm in the current tool frame, then turns it by dtheta rad
  /// (counter-clockwise). A move the arm cannot reach leaves it where it was and returns false, as
  /// a real arm's controller refuses a target beyond its joint limits; true when it moved.
  virtual bool move_relative(double dx, double dy, double dtheta) = 0;

 protected:
  Arm() = default;
  Arm(const Arm&) = default;
  Arm& operator=(const Arm&) = default;
};

}  // namespace neopipe::nav
