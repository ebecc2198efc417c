#include "nav/mapmaker/trajectories.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace neopipe::nav::mapmaker {

std::optional<double> entry_distance(const WindowModel& window, const Eigen::Vector2d& start,
                                     const Eigen::Vector2d& direction, const Eigen::Vector2d& p) {
  // p is inside at t when start_k + t u_k < p_k < start_k + a + t u_k on both axes: an open interval
  // of t per axis; p enters at the start of their intersection.
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    const double near = p[k] - start[k] - window.side;  // t u_k must exceed this
    const double far = p[k] - start[k];                 // and stay below this
    const double u = direction[k];
    if (u == 0) {
      if (!(near < 0 && far > 0)) return std::nullopt;
      continue;
    }
    const double t0 = u > 0 ? near / u : far / u;
    const double t1 = u > 0 ? far / u : near / u;
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  if (!(lo < hi) || lo < 0) return std::nullopt;  // never inside, or inside at the start
  return lo;
}

std::optional<TrajectoryHit> first_entering(const ObjectGrid& grid, const WindowModel& window,
                                            const Eigen::Vector2d& start, const Eigen::Vector2d& direction,
                                            const Eigen::Vector2d& reference) {
  return first_entering(grid, window, start, direction, reference, {});
}

std::optional<TrajectoryHit> first_entering(const ObjectGrid& grid, const WindowModel& window,
                                            const Eigen::Vector2d& start, const Eigen::Vector2d& direction,
                                            const Eigen::Vector2d& reference, std::span<const std::uint32_t> ignore) {
  const std::span<const Eigen::Vector2d> objects = grid.objects();
  if (objects.empty()) return std::nullopt;
  // Sweep in segments of one cell: an object entering at t lies in the closure of the window at t,
  // so the hull of the window's positions over a segment holds every object entering during it.
  // Once the best entry found lies within the segment scanned, no later segment can beat it.
  const Eigen::Vector2d side(window.side, window.side);
  const Eigen::Vector2d world_lo = grid.lower();
  const Eigen::Vector2d world_hi = world_lo + Eigen::Vector2d(grid.columns() * grid.cell(), grid.rows() * grid.cell());
  const double step = grid.cell();
  std::optional<TrajectoryHit> best;
  for (double t0 = 0;; t0 += step) {
    const double t1 = t0 + step;
    const Eigen::Vector2d a = start + t0 * direction;
    const Eigen::Vector2d b = start + t1 * direction;
    const Eigen::Vector2d lo = a.cwiseMin(b);
    const Eigen::Vector2d hi = a.cwiseMax(b) + side;
    if ((hi.array() < world_lo.array()).any() || (lo.array() > world_hi.array()).any()) {
      // Past the objects' bounding box: only stop if moving away from it on that axis.
      const bool leaving = (direction.x() >= 0 ? lo.x() > world_hi.x() : hi.x() < world_lo.x()) ||
                           (direction.y() >= 0 ? lo.y() > world_hi.y() : hi.y() < world_lo.y());
      if (leaving) break;
    }
    grid.for_each_near(lo, hi, [&](std::uint32_t id) {
      if (std::binary_search(ignore.begin(), ignore.end(), id)) return;
      const auto t = entry_distance(window, start, direction, objects[id]);
      if (!t) return;
      if (!best || *t < best->slide ||
          (*t == best->slide && id != best->object && preferred(reference, objects[id], objects[best->object]))) {
        best = TrajectoryHit{id, *t};
      }
    });
    if (best && best->slide <= t1) break;
  }
  return best;
}

Eigen::Vector2d Trajectory::heading(const WorldViews& views) const {
  const Eigen::Vector2d d = (views.position(via) - views.position(from.object)).normalized();
  return direction == Direction::positive ? d : Eigen::Vector2d(-d);
}

std::optional<Trajectory> trajectory_from(const WorldViews& views, const Placement& from, Description description,
                                          Direction direction) {
  const auto via = views.landmark(from, description);
  if (!via) return std::nullopt;
  Trajectory t{from, *via, description, direction, 0, 0};
  const Eigen::Vector2d heading = t.heading(views);
  const auto hit =
      first_entering(views.grid(), views.window(), views.origin(from), heading, views.position(from.object));
  if (!hit) return std::nullopt;
  t.to = hit->object;
  t.slide = hit->slide;
  return t;
}

std::vector<Trajectory> all_trajectories(const WorldViews& views) {
  std::vector<Trajectory> out;
  for (std::uint32_t node = 0; node < 4 * views.object_count(); ++node) {
    const Placement p = Placement::of_node(node);
    const Description d = views.obvious(p) ? Description::Obvious : Description::Isol;
    for (const Direction dir : {Direction::positive, Direction::negative}) {
      if (auto t = trajectory_from(views, p, d, dir)) out.push_back(*t);
    }
  }
  return out;
}

}  // namespace neopipe::nav::mapmaker
