#include "sim/arm/motion_model.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace neopipe::sim {
namespace {

void check_coefficient(double value, const char* name) {
  if (!(std::isfinite(value) && value >= 0)) {
    throw std::invalid_argument(fmt::format("motion error {} = {} must be a finite number >= 0", name, value));
  }
}

}  // namespace

void validate(const MotionErrors& errors) {
  check_coefficient(errors.translation_sigma0, "translation_sigma0");
  check_coefficient(errors.along_per_mm, "along_per_mm");
  check_coefficient(errors.across_per_mm, "across_per_mm");
  check_coefficient(errors.rotation_sigma0, "rotation_sigma0");
  check_coefficient(errors.rotation_per_mm, "rotation_per_mm");
  check_coefficient(errors.rotation_per_rad, "rotation_per_rad");
}

ToolMove perturb(const MotionErrors& errors, const ToolMove& commanded, Random& random) {
  const double along_z = random.normal();
  const double across_z = random.normal();
  const double heading_z = random.normal();
  const double d = std::hypot(commanded.dx, commanded.dy);
  // Unit vectors along and across the commanded direction, in the tool frame.
  const double ux = d > 0 ? commanded.dx / d : 1.0;
  const double uy = d > 0 ? commanded.dy / d : 0.0;
  const double along = along_z * errors.along_sigma(d);
  const double across = across_z * errors.across_sigma(d);
  return {commanded.dx + ux * along - uy * across, commanded.dy + uy * along + ux * across,
          commanded.dtheta + heading_z * errors.rotation_sigma(d, commanded.dtheta)};
}

}  // namespace neopipe::sim
