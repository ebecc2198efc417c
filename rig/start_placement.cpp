#include "rig/start_placement.hpp"

#include <cmath>
#include <numbers>

#include "sim/panorama.hpp"

namespace neopipe::rig {
namespace {

// Whether `p` keeps `clear` from every marble's centre and is nearer `id` than any other by `margin`.
bool in_cell_and_clear(const sim::World& world, std::uint32_t id, const Eigen::Vector2d& p, double clear,
                       double margin) {
  const double own = (p - world.objects[id]).norm();
  for (std::size_t j = 0; j < world.objects.size(); ++j) {
    const double d = (p - world.objects[j]).norm();
    if (d < clear) return false;
    if (j != id && d < own + margin) return false;
  }
  return true;
}

}  // namespace

std::optional<Eigen::Vector2d> clear_start_offset(const sim::World& world, std::uint32_t id, double margin) {
  const double clear = world.marble_diameter / 2 + sim::kMinClearanceMm + margin;
  for (double r = clear; r <= clear + 40; r += 5) {
    for (int deg = 0; deg < 360; deg += 15) {
      const double a = deg * std::numbers::pi / 180;
      const Eigen::Vector2d offset = r * Eigen::Vector2d(std::cos(a), std::sin(a));
      if (in_cell_and_clear(world, id, world.objects[id] + offset, clear, 2 * margin)) return offset;
    }
  }
  return std::nullopt;
}

}  // namespace neopipe::rig
