#pragma once
// A pose in the workspace plane: the tool frame (or a camera looking straight down) at (x, y) mm,
// its x axis turned theta radians counter-clockwise from the world's East.

#include <cmath>

namespace neopipe::sim {

struct Pose2 {
  double x = 0;      ///< mm, East
  double y = 0;      ///< mm, North
  double theta = 0;  ///< rad, counter-clockwise from East
};

/// The pose reached by moving (dx, dy) in `from`'s tool frame and then turning by dtheta.
inline Pose2 compose(const Pose2& from, double dx, double dy, double dtheta) {
  const double c = std::cos(from.theta);
  const double s = std::sin(from.theta);
  return {from.x + c * dx - s * dy, from.y + s * dx + c * dy, from.theta + dtheta};
}

}  // namespace neopipe::sim
