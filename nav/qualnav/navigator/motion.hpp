#pragma once
// Moves that keep the clearance, and ranges by parallax (qualnav.md §2, §6).
//
// Clearance: the robot keeps sim's 10 mm from every marble's surface. A landmark's centre lies on
// the segment of its bearing between range_lo and range_hi (the interval holds the truth), so a move
// is safe when its whole track keeps r_m + clearance + margin from every such segment — or, for a
// marble it is already nearer than that (the start beside a marble), does not come nearer.
//
// Parallax: the range estimate may carry a large error, the bearing only ~0.2°. Two looks a short
// sideways move apart give the range by triangulation, independent of the range error: the a
// heading's stop at 15 mm and the offset the navigator claims use it.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

struct ClearanceRule {
  double marble_radius_mm = 2.5;
  double clearance_mm = 10;
  double margin_mm = 1.5;
  [[nodiscard]] double required() const { return marble_radius_mm + clearance_mm + margin_mm; }
};

/// The least distance from a move's track (origin → `end`, tool frame) to where `l` may lie.
double track_gap(const ViewedLandmark& l, const Eigen::Vector2d& end);
/// The least distance from the origin to where `l` may lie.
double current_gap(const ViewedLandmark& l);

/// The move (tool frame, mm) nearest `bearing` that keeps the clearance of every landmark of `view`
/// except `ignore`: `length` along bearing, then turned ±15°, ±30°, ... 180° (backing away is
/// a move too), then the same at half length.
/// nullopt when none is safe.
std::optional<Eigen::Vector2d> safe_move(const Viewframe& view, double bearing, double length,
                                         const ClearanceRule& rule, std::optional<LandmarkId> ignore = std::nullopt);

/// The range of a landmark seen at `bearing0` from the origin and at `bearing1` after moving by
/// `move` (tool frame, no turn): its distance from the second position. nullopt for rays that do
/// not meet ahead of both (parallel, or diverging).
std::optional<double> parallax_range(double bearing0, const Eigen::Vector2d& move, double bearing1);

}  // namespace neopipe::nav::qualnav
