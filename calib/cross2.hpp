#pragma once
// The 2-D cross product (z of the 3-D one): twice a triangle's signed area, the sine of a turn.

#include <Eigen/Core>

namespace neopipe::calib {

inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace neopipe::calib
