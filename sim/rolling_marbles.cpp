#include "sim/rolling_marbles.hpp"

#include <cmath>
#include <numbers>

#include "sim/neighbour_grid.hpp"
#include "sim/random.hpp"

namespace neopipe::sim {

RollingMarbles::RollingMarbles(const World& world, double speed, std::uint64_t seed)
    : size_(world.size), diameter_(world.marble_diameter), positions_(world.objects), speed_(speed) {
  Random rng(seed ^ 0x726F6C6CULL);  // "roll"
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    const double heading = rng.uniform(0, 2 * std::numbers::pi);
    velocities_.emplace_back(speed * std::cos(heading), speed * std::sin(heading));
  }
}

void RollingMarbles::step(double dt) {
  if (speed_ <= 0 || positions_.empty()) return;
  const int n = std::max(1, static_cast<int>(std::ceil(speed_ * dt / (0.1 * diameter_))));
  for (int i = 0; i < n; ++i) substep(dt / n);
}

void RollingMarbles::substep(double dt) {
  const double r = diameter_ / 2;
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    auto& p = positions_[i];
    auto& v = velocities_[i];
    p += v * dt;
    for (int k = 0; k < 2; ++k) {
      if (p[k] < r) {
        p[k] = 2 * r - p[k];
        v[k] = std::abs(v[k]);
      } else if (p[k] > size_[k] - r) {
        p[k] = 2 * (size_[k] - r) - p[k];
        v[k] = -std::abs(v[k]);
      }
    }
  }
  // Collisions, in index order (deterministic): equal masses exchange their velocity components
  // along the line of centres, and the pair is pushed apart to touching.
  NeighbourGrid grid(size_, diameter_);
  for (std::size_t i = 0; i < positions_.size(); ++i) grid.insert(positions_[i], i);
  for (std::size_t i = 0; i < positions_.size(); ++i) {
    grid.for_each_within(positions_[i], diameter_, [&](std::size_t j) {
      if (j <= i) return;
      Eigen::Vector2d n = positions_[j] - positions_[i];
      const double d = n.norm();
      if (d >= diameter_ || d < 1e-12) return;
      n /= d;
      const double approach = (velocities_[i] - velocities_[j]).dot(n);
      if (approach > 0) {
        velocities_[i] -= approach * n;
        velocities_[j] += approach * n;
      }
      const double push = (diameter_ - d) / 2;
      positions_[i] -= push * n;
      positions_[j] += push * n;
    });
  }
}

}  // namespace neopipe::sim
