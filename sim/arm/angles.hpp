#pragma once
// Angle units and representatives. The arm computes in radians; people read and type degrees, so
// configuration defaults, messages, the command line and the report use degrees.

#include <cmath>
#include <numbers>
#include <optional>

namespace neopipe::sim {

constexpr double radians(double deg) {
  return deg * (std::numbers::pi / 180.0);
}
constexpr double degrees(double rad) {
  return rad * (180.0 / std::numbers::pi);
}

/// `angle` wrapped into (-pi, pi].
inline double wrap_pi(double angle) {
  const double two_pi = 2 * std::numbers::pi;
  double a = std::remainder(angle, two_pi);  // [-pi, pi]
  if (a <= -std::numbers::pi) a += two_pi;
  return a;
}

/// The angle equal to `angle` modulo 2 pi that lies in [lo, hi] (up to `tolerance`), choosing the one
/// nearest the middle of the range when it holds several; nullopt when none does.
inline std::optional<double> representative_in(double angle, double lo, double hi, double tolerance = 1e-12) {
  const double two_pi = 2 * std::numbers::pi;
  const double mid = (lo + hi) / 2;
  const double candidate = angle + two_pi * std::round((mid - angle) / two_pi);
  if (std::abs(candidate - mid) <= (hi - lo) / 2 + tolerance) return candidate;
  return std::nullopt;
}

}  // namespace neopipe::sim
