#pragma once
// Trajectories (park-kender.md §4, paper §4.4-4.5): with the reference P1 held at a corner and a
// described landmark P2 in view, the navigator slides its window along P1->P2 (Trajp) or P2->P1
// (Trajn); the first object to enter the window is the trajectory's goal. Found here by exact
// geometry: each object's entry time into the sliding open box, the smallest one wins.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/common/landmarks.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

struct TrajectoryHit {
  std::uint32_t object = 0;  ///< the first object to enter
  double slide = 0;          ///< how far the window slid when it entered, mm
};

/// The first object (not in view at the start) to enter the open window of side window.side whose
/// lower-left corner starts at `start` and moves along the unit vector `direction`. Ties in entry
/// distance go to the object preferred from `reference` (landmarks.hpp). None when no object ever
/// enters, i.e. the window leaves the world without meeting one.
std::optional<TrajectoryHit> first_entering(const ObjectGrid& grid, const WindowModel& window,
                                            const Eigen::Vector2d& start, const Eigen::Vector2d& direction,
                                            const Eigen::Vector2d& reference);
/// The same, not counting the objects in `ignore` (ascending ids): what the navigator already knows,
/// the reference and the direction landmark, cannot be mistaken for the goal when they re-enter.
std::optional<TrajectoryHit> first_entering(const ObjectGrid& grid, const WindowModel& window,
                                            const Eigen::Vector2d& start, const Eigen::Vector2d& direction,
                                            const Eigen::Vector2d& reference, std::span<const std::uint32_t> ignore);

/// Entry distance of `p` into the window sliding from `start` along `direction`: the smallest t >= 0
/// at which p is strictly inside; none if it never is or is already inside at t = 0.
std::optional<double> entry_distance(const WindowModel& window, const Eigen::Vector2d& start,
                                     const Eigen::Vector2d& direction, const Eigen::Vector2d& p);

struct Trajectory {
  Placement from;                               ///< the reference and the corner it is held at
  std::uint32_t via = 0;                        ///< the described landmark that gives the direction with the reference
  Description description = Description::Isol;  ///< how the navigator finds `via`
  Direction direction = Direction::positive;
  std::uint32_t to = 0;  ///< the goal: the first object to enter
  double slide = 0;      ///< window travel until the goal enters, mm

  /// Unit vector of the slide in world coordinates.
  Eigen::Vector2d heading(const WorldViews& views) const;
};

/// The trajectory from placement `from` using the landmark `description` selects there, in
/// direction `direction`; none when that landmark does not exist or nothing enters.
std::optional<Trajectory> trajectory_from(const WorldViews& views, const Placement& from, Description description,
                                          Direction direction);

/// Every trajectory of the world: for each object and corner, with the isolated landmark as the
/// second landmark (which is the obvious one wherever that exists: with one object in view besides
/// the reference both descriptors pick it, and the map records Obvious), in both directions.
std::vector<Trajectory> all_trajectories(const WorldViews& views);

}  // namespace neopipe::nav::mapmaker
