#include "sim/arm/scara.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace neopipe::sim {
namespace {

void check_limits(const JointLimits& limits, const char* joint) {
  if (!(std::isfinite(limits.min) && std::isfinite(limits.max) && limits.min <= limits.max)) {
    throw std::invalid_argument(fmt::format("{} limits {:.2f}..{:.2f} deg are not a finite range min <= max", joint,
                                            degrees(limits.min), degrees(limits.max)));
  }
}

/// Distance from the shoulder axis to the tool axis at elbow angle magnitude `bend` (law of
/// cosines written with cos(bend/2), which keeps full precision near the stretched arm).
double reach_at(double l1, double l2, double bend) {
  const double c = std::cos(bend / 2);
  return std::sqrt((l1 - l2) * (l1 - l2) + 4 * l1 * l2 * c * c);
}

/// The nearest representative of `angle` to the middle of `limits`: the value a message shows.
double nearest_to(double angle, const JointLimits& limits) {
  const double two_pi = 2 * std::numbers::pi;
  return angle + two_pi * std::round(((limits.min + limits.max) / 2 - angle) / two_pi);
}

}  // namespace

Scara::Scara(ScaraGeometry geometry) : geometry_(std::move(geometry)) {
  const ScaraGeometry& g = geometry_;
  if (!g.base.allFinite()) throw std::invalid_argument("the arm's base position is not finite");
  if (!(std::isfinite(g.l1) && g.l1 > 0 && std::isfinite(g.l2) && g.l2 > 0)) {
    throw std::invalid_argument(fmt::format("link lengths l1 = {} mm, l2 = {} mm must be positive", g.l1, g.l2));
  }
  check_limits(g.shoulder, "shoulder");
  check_limits(g.elbow, "elbow");
  check_limits(g.roll, "roll");
  if (g.elbow.min < -std::numbers::pi || g.elbow.max > std::numbers::pi) {
    throw std::invalid_argument(fmt::format("elbow limits {:.2f}..{:.2f} deg go beyond -180..180 deg",
                                            degrees(g.elbow.min), degrees(g.elbow.max)));
  }
  // The magnitudes |q2| allowed on the side of the configured bend.
  if (g.bend == ElbowBend::positive) {
    elbow_lo_ = std::max(g.elbow.min, 0.0);
    elbow_hi_ = g.elbow.max;
  } else {
    elbow_lo_ = std::max(-g.elbow.max, 0.0);
    elbow_hi_ = -g.elbow.min;
  }
  if (!(elbow_lo_ <= elbow_hi_)) {
    throw std::invalid_argument(fmt::format("elbow limits {:.2f}..{:.2f} deg allow no {} elbow angle",
                                            degrees(g.elbow.min), degrees(g.elbow.max),
                                            g.bend == ElbowBend::positive ? "positive" : "negative"));
  }
  max_reach_ = reach_at(g.l1, g.l2, elbow_lo_);
  min_reach_ = reach_at(g.l1, g.l2, elbow_hi_);
}

Eigen::Vector2d Scara::elbow_position(const JointAngles& q) const {
  return geometry_.base + geometry_.l1 * Eigen::Vector2d(std::cos(q.shoulder), std::sin(q.shoulder));
}

Pose2 Scara::forward(const JointAngles& q) const {
  const double forearm = q.shoulder + q.elbow;
  const Eigen::Vector2d tool = elbow_position(q) + geometry_.l2 * Eigen::Vector2d(std::cos(forearm), std::sin(forearm));
  return {tool.x(), tool.y(), forearm + q.roll};
}

std::variant<JointAngles, std::string> Scara::solve(const Pose2& tool) const {
  const ScaraGeometry& g = geometry_;
  if (!(std::isfinite(tool.x) && std::isfinite(tool.y) && std::isfinite(tool.theta))) {
    return fmt::format("pose ({}, {}, {} deg) is not finite", tool.x, tool.y, degrees(tool.theta));
  }
  const double dx = tool.x - g.base.x();
  const double dy = tool.y - g.base.y();
  const double r = std::hypot(dx, dy);
  // Rounding alone must not reject a point on the reach boundary; anything farther out is a miss.
  const double tolerance = 1e-12 * (g.l1 + g.l2);
  if (r > max_reach_ + tolerance || r < min_reach_ - tolerance) {
    return fmt::format(
        "pose ({:.2f}, {:.2f}) is {:.2f} mm from the base ({:.2f}, {:.2f}); the arm reaches {:.2f}..{:.2f} mm", tool.x,
        tool.y, r, g.base.x(), g.base.y(), min_reach_, max_reach_);
  }
  // |q2| from tan^2(q2/2) = ((l1+l2)^2 - r^2) / (r^2 - (l1-l2)^2), factored so that neither end of
  // the reach loses precision the way acos of the law of cosines does.
  const double sum = g.l1 + g.l2;
  const double diff = std::abs(g.l1 - g.l2);
  const double bend_magnitude = std::clamp(2 * std::atan2(std::sqrt(std::max(0.0, (sum - r) * (sum + r))),
                                                          std::sqrt(std::max(0.0, (r - diff) * (r + diff)))),
                                           elbow_lo_, elbow_hi_);
  const double elbow = g.bend == ElbowBend::positive ? bend_magnitude : -bend_magnitude;
  const double shoulder_unwrapped =
      std::atan2(dy, dx) - std::atan2(g.l2 * std::sin(elbow), g.l1 + g.l2 * std::cos(elbow));
  const auto shoulder = representative_in(shoulder_unwrapped, g.shoulder.min, g.shoulder.max);
  if (!shoulder) {
    return fmt::format(
        "pose ({:.2f}, {:.2f}) needs the shoulder at {:.2f} deg (elbow {:.2f} deg); its limits are "
        "{:.2f}..{:.2f} deg",
        tool.x, tool.y, degrees(nearest_to(shoulder_unwrapped, g.shoulder)), degrees(elbow), degrees(g.shoulder.min),
        degrees(g.shoulder.max));
  }
  const double roll_unwrapped = tool.theta - *shoulder - elbow;
  const auto roll = representative_in(roll_unwrapped, g.roll.min, g.roll.max);
  if (!roll) {
    return fmt::format(
        "heading {:.2f} deg at ({:.2f}, {:.2f}) needs the roll at {:.2f} deg; its limits are "
        "{:.2f}..{:.2f} deg",
        degrees(tool.theta), tool.x, tool.y, degrees(nearest_to(roll_unwrapped, g.roll)), degrees(g.roll.min),
        degrees(g.roll.max));
  }
  return JointAngles{*shoulder, elbow, *roll};
}

JointAngles Scara::inverse(const Pose2& tool) const {
  auto solution = solve(tool);
  if (auto* why = std::get_if<std::string>(&solution)) throw ReachError(*why);
  return std::get<JointAngles>(solution);
}

bool Scara::reachable(const Pose2& tool) const {
  return std::holds_alternative<JointAngles>(solve(tool));
}

}  // namespace neopipe::sim
