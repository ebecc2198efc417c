#include "sim/arm/scara_sizing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace neopipe::sim {

ScaraGeometry scara_for_workspace(const Eigen::Vector2d& size) {
  if (!(size.allFinite() && size.x() > 0 && size.y() > 0)) {
    throw std::invalid_argument(fmt::format("workspace {} x {} mm: the size must be positive", size.x(), size.y()));
  }
  const double s = std::max(size.x(), size.y());
  const double margin = 0.05 * s;
  const double standoff = 0.2 * s;
  ScaraGeometry g;  // keeps the default joint limits and bend
  g.base = {size.x() / 2, -margin - standoff};
  const double farthest = std::hypot(size.x() / 2 + margin, size.y() + 2 * margin + standoff);
  // Round numbers for a person reading the geometry; rounding up only adds reach.
  const double step = s / 20;
  g.l1 = g.l2 = step * std::ceil(0.525 * farthest / step);
  return g;
}

}  // namespace neopipe::sim
