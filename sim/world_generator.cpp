#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "sim/neighbour_grid.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace neopipe::sim {
namespace {

// Random sequential addition of disks jams at a covered fraction of about 0.547 (Feder 1980); past
// that no new disk fits anywhere, and near it the redraws grow without bound.
constexpr double kJammingCoverage = 0.547;

double micrometres(double mm) {
  return std::round(mm * 1000.0) / 1000.0;
}

}  // namespace

World generate_world(const WorldRequest& q) {
  const std::string what = fmt::format("world of {} marbles in {} x {} mm", q.objects, q.size.x(), q.size.y());
  if (q.objects < 0) throw WorldError(what + ": the number of objects cannot be negative");
  if (!(q.size.x() > 0 && q.size.y() > 0)) throw WorldError(what + ": the workspace size must be positive");
  if (!(q.marble_diameter > 0)) throw WorldError(what + ": the marble diameter must be positive");
  if (!(q.min_gap >= 0)) throw WorldError(what + ": the minimum gap cannot be negative");
  const double d = q.marble_diameter;
  if (q.size.x() < d || q.size.y() < d) throw WorldError(what + ": a marble is wider than the workspace");
  // Each marble keeps a disk of diameter d + gap free of other centres; centres lie in the workspace
  // shrunk by a radius on every side, so the disks' room is that area grown by half the spacing.
  const double spacing = d + q.min_gap;
  const double room = (q.size.x() - d + spacing) * (q.size.y() - d + spacing);
  const double fits = kJammingCoverage * room / (std::numbers::pi * spacing * spacing / 4);
  if (q.objects > 0.9 * fits) {
    throw WorldError(fmt::format("{}: do not fit with diameter {} mm and gap {} mm (random placement jams at about {})",
                                 what, d, q.min_gap, static_cast<long>(fits)));
  }
  World w;
  w.size = q.size;
  w.marble_diameter = d;
  w.objects.reserve(static_cast<std::size_t>(q.objects));
  Random rng(q.seed);
  NeighbourGrid grid(q.size, spacing);
  const double r = d / 2;
  const long max_draws = std::max(1'000'000L, 2000L * q.objects);
  long draws = 0;
  while (std::ssize(w.objects) < q.objects) {
    if (++draws > max_draws) {
      throw WorldError(fmt::format("{}: placed only {} after {} random draws; ask for fewer or a smaller gap", what,
                                   w.objects.size(), max_draws));
    }
    // Rounded into [r, W - r] so the file's micrometre values are the positions themselves.
    const Eigen::Vector2d p(std::clamp(micrometres(rng.uniform(r, q.size.x() - r)), r, q.size.x() - r),
                            std::clamp(micrometres(rng.uniform(r, q.size.y() - r)), r, q.size.y() - r));
    if (grid.any_within(p, spacing)) continue;
    grid.insert(p, w.objects.size());
    w.objects.push_back(p);
  }
  return w;
}

}  // namespace neopipe::sim
