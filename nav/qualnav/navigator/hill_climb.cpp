#include "nav/qualnav/navigator/hill_climb.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace neopipe::nav::qualnav {

std::optional<ClimbState> climb_state(const Viewframe& now, const Viewframe& goal) {
  std::vector<std::pair<const ViewedLandmark*, const ViewedLandmark*>> seen;  // (now, goal), goal's pan order
  for (const ViewedLandmark& g : goal.landmarks) {
    if (const ViewedLandmark* n = now.find(g.id)) seen.emplace_back(n, &g);
  }
  if (seen.size() < 2) return std::nullopt;
  double cost = 0;
  double worst = 0;
  double gx = 0;
  double gy = 0;
  int pairs = 0;
  const auto grad_bearing = [](const ViewedLandmark& l) -> Eigen::Vector2d {
    // β = atan2(L − P): ∂β/∂P = (sin β, −cos β) / r.
    return Eigen::Vector2d(std::sin(l.bearing), -std::cos(l.bearing)) / l.range_mid();
  };
  for (std::size_t k = 0; k + 1 < seen.size(); ++k) {
    const auto [a, ga] = seen[k];
    const auto [b, gb] = seen[k + 1];
    const double error = wrap_angle(angle_between(*a, *b) - angle_between(*ga, *gb));
    cost += error * error;
    worst = std::max(worst, std::abs(error));
    const Eigen::Vector2d g = 2 * error * (grad_bearing(*b) - grad_bearing(*a));
    gx += g.x();
    gy += g.y();
    ++pairs;
  }
  return ClimbState{cost, worst, Eigen::Vector2d(gx, gy), pairs};
}

Eigen::Vector2d climb_step(const ClimbState& state, const HillClimbSettings& settings) {
  const double norm = state.gradient.norm();
  if (!(norm > 0)) return Eigen::Vector2d::Zero();
  return -state.gradient / norm * settings.step_mm;
}

}  // namespace neopipe::nav::qualnav
