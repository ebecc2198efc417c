#include "nav/mapmaker/workspace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace neopipe::nav::mapmaker {

void check_workspace(const Workspace& workspace, const std::string& origin) {
  const Eigen::Vector2d& size = workspace.size;
  if (!(std::isfinite(size.x()) && std::isfinite(size.y()) && size.x() > 0 && size.y() > 0)) {
    throw MapError(fmt::format("{}: workspace size {}x{} must be positive", origin, size.x(), size.y()));
  }
  for (std::size_t i = 0; i < workspace.objects.size(); ++i) {
    const Eigen::Vector2d& p = workspace.objects[i];
    if (!(p.allFinite() && p.x() >= 0 && p.y() >= 0 && p.x() <= size.x() && p.y() <= size.y())) {
      throw MapError(fmt::format("{}: object {} at ({}, {}) lies outside the {}x{} mm workspace", origin, i, p.x(),
                                 p.y(), size.x(), size.y()));
    }
  }
  // Two objects at one place would be one blob to any camera: a corrupt input, not a world.
  std::vector<std::size_t> order(workspace.objects.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto& o = workspace.objects;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return o[a].x() != o[b].x() ? o[a].x() < o[b].x() : (o[a].y() != o[b].y() ? o[a].y() < o[b].y() : a < b);
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (o[order[k]] == o[order[k - 1]]) {
      throw MapError(fmt::format("{}: objects {} and {} are at the same place ({}, {})", origin,
                                 std::min(order[k], order[k - 1]), std::max(order[k], order[k - 1]), o[order[k]].x(),
                                 o[order[k]].y()));
    }
  }
}

}  // namespace neopipe::nav::mapmaker
