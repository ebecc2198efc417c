#pragma once
// The arm's motion errors: what a relative move in the tool frame really does.

#include <cmath>

#include "sim/arm/angles.hpp"
#include "sim/random.hpp"

namespace neopipe::sim {

/// A relative move in the tool frame at its start: translate by (dx, dy) mm, then turn by dtheta
/// rad (as sim::compose does).
struct ToolMove {
  double dx = 0;
  double dy = 0;
  double dtheta = 0;
};

/// Each move of length d = |(dx, dy)| and turn dtheta gets three independent zero-mean Gaussian
/// errors, in the tool frame at the start of the move:
///   along the commanded direction:      sigma_along  = translation_sigma0 + along_per_mm  * d
///   across it (90 deg counter-clockwise): sigma_across = translation_sigma0 + across_per_mm * d
///   of the heading after the move:      sigma_theta  = rotation_sigma0 + rotation_per_mm * d
///                                                      + rotation_per_rad * |dtheta|
/// A pure turn (d = 0) takes the tool's x axis as "along". The heading error stays in the tool
/// frame and turns every later move: the navigator has no compass, so this drift is real.
///
/// Why sigma grows linearly with d rather than as sqrt(d) (a random walk): a relative move of an
/// arm is a single point-to-point motion whose error comes mostly from joint scale and link length
/// calibration, proportional to the motion; sigma0 is the repeatability floor. One consequence:
/// splitting a move in two does not preserve its variance, as for a real calibrated arm.
///
/// Defaults: repeatability 0.05 mm; 0.3 mm of sigma per 100 mm, along and across; heading 0.05 deg
/// per move plus 0.2 deg per 100 mm moved plus 0.5% of the commanded turn. none() has no errors.
struct MotionErrors {
  double translation_sigma0 = 0.05;         ///< mm
  double along_per_mm = 0.003;              ///< mm of sigma per mm moved
  double across_per_mm = 0.003;             ///< mm of sigma per mm moved
  double rotation_sigma0 = radians(0.05);   ///< rad
  double rotation_per_mm = radians(0.002);  ///< rad of sigma per mm moved
  double rotation_per_rad = 0.005;          ///< rad of sigma per rad turned

  static constexpr MotionErrors none() { return {0, 0, 0, 0, 0, 0}; }

  double along_sigma(double distance) const { return translation_sigma0 + along_per_mm * distance; }
  double across_sigma(double distance) const { return translation_sigma0 + across_per_mm * distance; }
  double rotation_sigma(double distance, double turn) const {
    return rotation_sigma0 + rotation_per_mm * distance + rotation_per_rad * std::abs(turn);
  }
};

/// Throws std::invalid_argument naming the field unless every coefficient is finite and >= 0.
void validate(const MotionErrors& errors);

/// The move the arm actually makes when `commanded` is asked for. Draws exactly three standard
/// normals from `random` (along, across, heading) whatever the sigmas, so that one error setting
/// never shifts another's draws, and zero sigmas give exactly the commanded move.
ToolMove perturb(const MotionErrors& errors, const ToolMove& commanded, Random& random);

}  // namespace neopipe::sim
