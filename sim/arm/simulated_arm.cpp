#include "sim/arm/simulated_arm.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace neopipe::sim {
namespace {

const MotionErrors& validated(const MotionErrors& errors) {
  validate(errors);
  return errors;
}

}  // namespace

SimulatedArm::SimulatedArm(const ScaraGeometry& geometry, const MotionErrors& errors, std::uint64_t seed,
                           const Pose2& start)
    : scara_(geometry),
      errors_(validated(errors)),
      random_(seed),
      pose_(start),
      commanded_(start),
      joints_(scara_.inverse(start)) {}

void SimulatedArm::move_relative(double dx, double dy, double dtheta) {
  if (!(std::isfinite(dx) && std::isfinite(dy) && std::isfinite(dtheta))) {
    throw std::invalid_argument(fmt::format("move ({}, {}, {} deg) is not finite", dx, dy, degrees(dtheta)));
  }
  // Work on copies and commit only when the target is reachable: a refused move leaves no trace.
  Random random = random_;
  const ToolMove actual = perturb(errors_, {dx, dy, dtheta}, random);
  const Pose2 target = compose(pose_, actual.dx, actual.dy, actual.dtheta);
  JointAngles joints;
  try {
    joints = scara_.inverse(target);
  } catch (const ReachError& e) {
    throw ReachError(fmt::format("move ({:.2f}, {:.2f}, {:.2f} deg) from ({:.2f}, {:.2f}, {:.2f} deg): {}", dx, dy,
                                 degrees(dtheta), pose_.x, pose_.y, degrees(pose_.theta), e.what()));
  }
  pose_ = target;
  joints_ = joints;
  commanded_ = compose(commanded_, dx, dy, dtheta);
  random_ = random;
}

void SimulatedArm::move_to(const Pose2& pose) {
  joints_ = scara_.inverse(pose);
  pose_ = pose;
  commanded_ = pose;
}

}  // namespace neopipe::sim
