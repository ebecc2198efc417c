#pragma once
// The harness's part of Qualnav (qualnav.md §7): the routes it teaches and the viewpaths recorded
// along them. The Qualnav simulator's user clicked a path; here the harness plans one on the true
// world — the shortest way on a 2 mm grid that keeps `route_clearance_mm` from every marble's
// surface (more than the robot's 10 mm, so the navigator, which strays from the route, starts with
// room to spare), straightened where a straight line keeps the same clearance — and records a
// viewframe every 20 mm along it with the panoramic sensor, its compass and its range error.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "nav/qualnav/metric/viewframe.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// The panoramic sensor as Qualnav reads it: range estimates scaled by a random factor, log-uniform
/// in [1/(1+e), 1+e], one draw per sighting, and intervals [d̂/(1+e), (1+e)·d̂] (qualnav.md §2: the
/// papers' 50 % is e = 0.5). The ring's own estimate from the disc size is nearly exact, so without
/// this error the intervals would be needlessly wide and the test of the papers' claim hollow.
struct QualnavSensing {
  double range_error = 0.5;      ///< e
  double bearing_noise_deg = 0;  ///< the sensor's configured bearing noise
};

/// The disc-size estimate itself errs by a few percent (pixel areas); the intervals allow for it.
inline constexpr double kRangeEstimateSlack = 0.05;
/// The navigator's intervals for a range error e: [d̂ / f, f · d̂] with f = 1 + e + kRangeEstimateSlack.
double qualnav_interval_factor(double range_error);

/// The harness's route from `from` to within `end_mm` (±2 mm) of `goal`'s centre keeping
/// `clearance_mm` from every marble's surface (the grid's cells are 2 mm; `from` itself may be
/// nearer a marble than that, by up to the margin the start placement leaves). nullopt when there
/// is none. The polyline starts at `from`.
std::optional<std::vector<Eigen::Vector2d>> teach_route(const sim::World& world, const Eigen::Vector2d& from,
                                                        std::uint32_t goal, double clearance_mm, double end_mm);

/// The same to within `end_mm` ± `tolerance_mm` of a point.
std::optional<std::vector<Eigen::Vector2d>> teach_route_to(const sim::World& world, const Eigen::Vector2d& from,
                                                           const Eigen::Vector2d& target, double clearance_mm,
                                                           double end_mm, double tolerance_mm);

/// A roundabout route, as a user clicking a path through the workspace might teach: first to near
/// the point 0.4 · |goal − from| to the `side` (+1 left, −1 right) of the midpoint, then to the goal.
/// It leaves the navigator shortcuts to find (qualnav.md §10's experiment).
std::optional<std::vector<Eigen::Vector2d>> teach_detour(const sim::World& world, const Eigen::Vector2d& from,
                                                         std::uint32_t goal, double clearance_mm, double end_mm,
                                                         double side);

/// Points every `spacing_mm` along a polyline, its first point first and its last point last.
std::vector<Eigen::Vector2d> sample_route(const std::vector<Eigen::Vector2d>& route, double spacing_mm);

/// The length of a polyline, and the sum of the absolute turns at its vertices (rad).
double route_length(const std::vector<Eigen::Vector2d>& route);
double route_turning(const std::vector<Eigen::Vector2d>& route);

/// The viewframes recorded at `points` (tool heading 0): each ring rendered by the simulator, read by
/// the engine's panorama graph, its ranges distorted by `sensing`, the compass read with its 1° error.
std::vector<nav::qualnav::Viewframe> record_viewpath(const sim::World& world,
                                                     const std::vector<Eigen::Vector2d>& points,
                                                     const QualnavSensing& sensing, std::uint64_t seed);

/// Scales each sighting's range estimate by a factor log-uniform in [1/(1+e), 1+e] from `u`
/// (uniform [0,1) draws). Shared by the recording and the journey's reading adapter.
template <typename Sightings, typename Uniform>
void apply_range_error(Sightings& sightings, double range_error, Uniform&& u) {
  if (!(range_error > 0)) return;
  const double span = std::log1p(range_error);
  for (auto& s : sightings) {
    const double f = std::exp(span * (2 * u() - 1));
    s.range_mm *= f;
  }
}

}  // namespace neopipe::rig
