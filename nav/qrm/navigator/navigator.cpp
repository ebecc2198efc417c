#include "nav/qrm/navigator/navigator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "nav/qrm/navigator/local_path.hpp"
#include "nav/qrm/rng.hpp"

namespace neopipe::nav::qrm {
namespace {

using Eigen::Vector2d;

constexpr double kRadiansPerDegree = std::numbers::pi / 180;
// Directions tried for a step, every 5° each side of the target's bearing: fine enough to slip
// between two marbles a clearance apart, coarse enough to cost nothing beside an image.
constexpr int kDirectionStepsDeg = 5;

// Where a sighting lies in the tool frame, from its bearing and range estimate.
Vector2d sighting_offset(const PanoramaSighting& s) {
  const double b = s.bearing_deg * kRadiansPerDegree;
  return s.range_mm * Vector2d(std::cos(b), std::sin(b));
}

// The nearest sighting by range estimate (equal estimates: the smaller id); null when none.
const PanoramaSighting* nearest_sighting(const std::vector<PanoramaSighting>& sightings) {
  const PanoramaSighting* best = nullptr;
  for (const PanoramaSighting& s : sightings) {
    if (best == nullptr || s.range_mm < best->range_mm || (s.range_mm == best->range_mm && s.id < best->id)) {
      best = &s;
    }
  }
  return best;
}

const PanoramaSighting* find_sighting(const std::vector<PanoramaSighting>& sightings, LandmarkId id) {
  const auto it =
      std::find_if(sightings.begin(), sightings.end(), [id](const PanoramaSighting& s) { return s.id == id; });
  return it == sightings.end() ? nullptr : &*it;
}

// The step toward `target` when the straight one is not allowed: along the shortest clear way into
// its cell (path_step), else the allowed direction, every 5° round, that most favours the target
// over the nearest other marble (cell_advantage), nearest the bearing among equals.
std::optional<Vector2d> detour_step(const std::vector<Obstacle>& obstacles, LandmarkId target,
                                    const Vector2d& target_at, double step, double keep) {
  if (std::optional<Vector2d> p = path_step(obstacles, target, target_at, step, keep);
      p && step_allowed(obstacles, *p, keep)) {
    return p;
  }
  const double bearing = std::atan2(target_at.y(), target_at.x());
  std::optional<Vector2d> best;
  double best_advantage = -std::numeric_limits<double>::infinity();
  for (int k = 1; k <= 180 / kDirectionStepsDeg; ++k) {
    for (const int side : {1, -1}) {
      if (side < 0 && k * kDirectionStepsDeg == 180) continue;
      const double a = bearing + side * k * kDirectionStepsDeg * kRadiansPerDegree;
      const Vector2d p = step * Vector2d(std::cos(a), std::sin(a));
      if (!step_allowed(obstacles, p, keep)) continue;
      const double v = cell_advantage(obstacles, target, target_at, p);
      if (v > best_advantage + 1e-9) {
        best_advantage = v;
        best = p;
      }
    }
  }
  return best;
}

// A step around the marble nearest the tool, keeping its distance (a tangent, counter-clockwise
// first), or turned outward from it by up to 90° where another marble bars the tangent: a look
// from elsewhere for a landmark it may hide.
std::optional<Vector2d> search_step(const std::vector<Obstacle>& obstacles, const Vector2d& nearest, double step,
                                    double keep) {
  const Vector2d out = -nearest.normalized();
  const Vector2d left(-out.y(), out.x());
  for (int k = 0; k <= 90 / kDirectionStepsDeg; ++k) {
    const double a = k * kDirectionStepsDeg * kRadiansPerDegree;
    for (const int side : {1, -1}) {
      const Vector2d p = step * (std::cos(a) * side * left + std::sin(a) * out);
      if (step_allowed(obstacles, p, keep)) return p;
    }
  }
  return std::nullopt;
}

// Whether `path` (from the landmark just reached) continues the remainder of `previous`.
bool same_remainder(const std::vector<LandmarkId>& previous, const std::vector<LandmarkId>& path) {
  if (path.empty()) return previous.empty();
  const auto at = std::find(previous.begin(), previous.end(), path.front());
  return at != previous.end() && std::equal(at, previous.end(), path.begin(), path.end());
}

}  // namespace

RingEye::RingEye(pipeline::io::FrameSource& camera, const PanoramaModel& model) : camera_(camera), reader_(model) {}

std::vector<PanoramaSighting> RingEye::look() {
  const auto frame = camera_.next();
  if (!frame) throw std::runtime_error("the panoramic camera gave no frame");
  return reader_.read(frame->image);
}

std::string_view navigation_ending_name(NavigationEnding e) {
  constexpr std::array<std::string_view, kNavigationEndings> names{"arrived", "no_path", "target_lost", "step_limit",
                                                                   "blocked"};
  return names.at(static_cast<std::size_t>(e));
}

std::vector<LandmarkSighting> landmark_sightings(const std::vector<PanoramaSighting>& sightings) {
  std::vector<LandmarkSighting> out;
  out.reserve(sightings.size());
  for (const PanoramaSighting& s : sightings) out.push_back({s.id, s.bearing_deg * kRadiansPerDegree, s.range_mm});
  return out;
}

NavigationReport navigate(RelationalMap& map, LandmarkId goal, Eye& eye, Arm& arm, const NavigatorConfig& config,
                          NavigationObserver* observer, std::span<const LandmarkId> planned) {
  NavigationReport report;
  const auto fail = [&](NavigationEnding e, std::string reason) {
    report.ending = e;
    report.reason = std::move(reason);
    return report;
  };
  const double keep = config.clearance_mm + config.marble_radius_mm + config.clearance_margin_mm;
  std::vector<PanoramaSighting> seen = eye.look();
  ++report.frames;
  const auto fuse = [&] {
    std::vector<PanoramaSighting> whole;
    std::copy_if(seen.begin(), seen.end(), std::back_inserter(whole),
                 [&](const PanoramaSighting& s) { return config.fuse_partial_sightings || !s.partial; });
    const ObservationReport o = observe(map, landmark_sightings(whole), config.observation);
    ++report.images_fused;
    report.inconsistent += o.inconsistent;
  };
  fuse();
  std::vector<LandmarkId> previous(planned.begin(), planned.end());
  while (true) {
    // (1) The landmark nearest now: the robot is in its Voronoi cell.
    const PanoramaSighting* here = nearest_sighting(seen);
    if (here == nullptr) return fail(NavigationEnding::target_lost, "no landmark in view");
    const LandmarkId start = here->id;
    report.reached.push_back(start);
    if (observer != nullptr) observer->landmark_reached(start, sighting_offset(*here));
    if (start == goal) return report;
    // (2) Dijkstra over the RNG estimated from the map as it is now.
    const std::vector<LandmarkId> path = plan_route(estimate_rng(map), start, goal);
    ++report.replans;
    if (report.first_route.empty()) report.first_route = path;
    if (path.size() < 2) {
      return fail(NavigationEnding::no_path, "the map's RNG estimate has no path from landmark " +
                                                 std::to_string(start) + " to landmark " + std::to_string(goal));
    }
    if (!previous.empty() && !same_remainder(previous, path)) ++report.reroutes;
    previous = path;
    // (3) Head for the next landmark until it is the nearest in view.
    const LandmarkId target = path[1];
    Vector2d target_at = Vector2d::Zero();
    int hidden = 0;
    int searched = 0;
    bool located = false;    // seen on this leg
    bool detouring = false;  // once the straight way was barred, the way round for the rest of the leg
    while (true) {
      const PanoramaSighting* t = find_sighting(seen, target);
      if (t != nullptr) {
        target_at = sighting_offset(*t);
        hidden = 0;
        located = true;
        if (nearest_sighting(seen)->id == target) break;
      } else if (located && ++hidden > config.hidden_looks) {
        located = false;  // where it was last seen is no guide any more: look for it
      }
      if (report.steps >= config.max_steps) {
        return fail(NavigationEnding::step_limit,
                    std::to_string(config.max_steps) + " steps without reaching landmark " + std::to_string(goal));
      }
      std::vector<Obstacle> obstacles;
      obstacles.reserve(seen.size() + 1);
      for (const PanoramaSighting& s : seen) obstacles.push_back({s.id, sighting_offset(s)});
      std::optional<Vector2d> step;
      bool detour = true;
      if (!located) {
        // Not in view: most likely behind the marble nearest the tool, whose disc is the largest.
        // Walk round that marble to see past it, for a while.
        const PanoramaSighting* near = nearest_sighting(seen);
        if (near == nullptr || searched >= config.search_steps) {
          return fail(NavigationEnding::target_lost, "landmark " + std::to_string(target) + " is not in view");
        }
        ++searched;
        ++report.searches;
        step = search_step(obstacles, sighting_offset(*near), config.step_mm, keep);
      } else {
        if (t == nullptr) obstacles.push_back({target, target_at});  // where it was last seen
        const Vector2d straight = config.step_mm * target_at.normalized();
        if (!detouring && step_allowed(obstacles, straight, keep)) {
          step = straight;
          detour = false;
        } else {
          detouring = true;
          step = detour_step(obstacles, target, target_at, config.step_mm, keep);
        }
      }
      if (!step) {
        return fail(NavigationEnding::blocked,
                    "no step keeps the clearance on the way to landmark " + std::to_string(target));
      }
      if (!arm.move_relative(step->x(), step->y(), 0)) {
        return fail(NavigationEnding::blocked, "the arm refused a step toward landmark " + std::to_string(target));
      }
      ++report.steps;
      report.detours += detour ? 1 : 0;
      target_at -= *step;  // where the target is now if the next image does not show it
      seen = eye.look();
      ++report.frames;
      if (report.steps % config.fuse_every == 0) fuse();
    }
  }
}

}  // namespace neopipe::nav::qrm
