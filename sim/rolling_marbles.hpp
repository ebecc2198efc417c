#pragma once
// Marbles rolling on the workspace for the global camera's moving-marble clips: each starts at its
// world position with a random heading at a common speed, bounces off the workspace's edges, and
// collides elastically with the others (equal masses), so marbles never overlap and every blob
// stays one marble.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sim/world.hpp"

namespace neopipe::sim {

class RollingMarbles {
 public:
  RollingMarbles(const World& world, double speed, std::uint64_t seed);
  /// Advances by dt seconds (in substeps short enough that no marble moves more than a tenth of a
  /// diameter at once).
  void step(double dt);
  [[nodiscard]] const std::vector<Eigen::Vector2d>& positions() const { return positions_; }
  /// mm/s; exposed so that the kinetic energy the model promises to keep can be checked.
  [[nodiscard]] const std::vector<Eigen::Vector2d>& velocities() const { return velocities_; }

 private:
  void substep(double dt);
  Eigen::Vector2d size_;
  double diameter_;
  std::vector<Eigen::Vector2d> positions_;
  std::vector<Eigen::Vector2d> velocities_;
  double speed_;
};

}  // namespace neopipe::sim
