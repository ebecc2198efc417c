#pragma once
// The navigator's way around marbles (internal to neopipe_qrm_navigator): in the tool frame, from
// the sightings' estimated positions only, the shortest way on a grid that keeps the clearance from
// every marble, into the target's (estimated) Voronoi cell.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "nav/qrm/relational_map.hpp"

namespace neopipe::nav::qrm {

/// A marble in view as the step rules see it: its id and estimated offset in the tool frame, mm.
struct Obstacle {
  LandmarkId id = 0;
  Eigen::Vector2d at;
};

/// Whether the tool may step to `p`: no marble's estimated centre within `keep` of it, unless the
/// step moves away from that marble (after an arm error the tool may already be too near).
bool step_allowed(const std::vector<Obstacle>& obstacles, const Eigen::Vector2d& p, double keep);

/// How much nearer `target` (at `target_at`) than every other marble the point `p` is, mm: positive
/// inside the target's Voronoi cell.
double cell_advantage(const std::vector<Obstacle>& obstacles, LandmarkId target, const Eigen::Vector2d& target_at,
                      const Eigen::Vector2d& p);

/// The first step of `step` mm along the shortest 8-connected path on a grid (cells of `cell` mm)
/// from the tool (the origin) to a cell at least `margin` mm inside the target's Voronoi cell,
/// every cell `keep` mm clear of every marble; none when there is no such path in the grid (which
/// reaches 80 mm beyond the target).
std::optional<Eigen::Vector2d> path_step(const std::vector<Obstacle>& obstacles, LandmarkId target,
                                         const Eigen::Vector2d& target_at, double step, double keep, double margin = 1,
                                         double cell = 2.5);

}  // namespace neopipe::nav::qrm
