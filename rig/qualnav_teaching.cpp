#include "rig/qualnav_teaching.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <tuple>

#include "nav/common/panorama_reading.hpp"
#include "nav/qualnav/navigator/view_source.hpp"
#include "sim/panorama.hpp"
#include "sim/random.hpp"

namespace neopipe::rig {
namespace {

using Eigen::Vector2d;

constexpr double kCellMm = 2;

// The least distance from `p` to any marble's centre.
double nearest_centre(const sim::World& world, const Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vector2d& o : world.objects) best = std::min(best, (o - p).norm());
  return best;
}

// Whether the straight segment a → b keeps `required` from every centre (sampled every 0.5 mm).
bool segment_clear(const sim::World& world, const Vector2d& a, const Vector2d& b, double required) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.5)));
  for (int i = 0; i <= n; ++i) {
    if (nearest_centre(world, a + (b - a) * (static_cast<double>(i) / n)) < required) return false;
  }
  return true;
}

}  // namespace

std::optional<std::vector<Vector2d>> teach_route(const sim::World& world, const Vector2d& from, std::uint32_t goal,
                                                 double clearance_mm, double end_mm) {
  return teach_route_to(world, from, world.objects.at(goal), clearance_mm, end_mm, kCellMm);
}

std::optional<std::vector<Vector2d>> teach_route_to(const sim::World& world, const Vector2d& from,
                                                    const Vector2d& target, double clearance_mm, double end_mm,
                                                    double tolerance_mm) {
  const double required = world.marble_diameter / 2 + clearance_mm;
  const int w = static_cast<int>(std::ceil(world.size.x() / kCellMm)) + 1;
  const int h = static_cast<int>(std::ceil(world.size.y() / kCellMm)) + 1;
  const auto at = [&](int i, int j) { return Vector2d(i * kCellMm, j * kCellMm); };
  std::vector<char> blocked(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i)
      blocked[static_cast<std::size_t>(j) * w + i] = nearest_centre(world, at(i, j)) < required;
  }
  const int si = std::clamp(static_cast<int>(std::lround(from.x() / kCellMm)), 0, w - 1);
  const int sj = std::clamp(static_cast<int>(std::lround(from.y() / kCellMm)), 0, h - 1);
  const auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * w + i; };
  const auto done = [&](int i, int j) { return std::abs((at(i, j) - target).norm() - end_mm) <= tolerance_mm; };
  const auto heuristic = [&](int i, int j) {
    return std::max(0.0, (at(i, j) - target).norm() - end_mm - tolerance_mm);
  };
  std::vector<double> cost(blocked.size(), std::numeric_limits<double>::infinity());
  std::vector<std::size_t> parent(blocked.size(), blocked.size());
  using Entry = std::tuple<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  cost[index(si, sj)] = 0;
  open.emplace(heuristic(si, sj), index(si, sj));
  std::optional<std::size_t> reached;
  while (!open.empty()) {
    const auto [f, u] = open.top();
    open.pop();
    const int ui = static_cast<int>(u % w);
    const int uj = static_cast<int>(u / w);
    if (f > cost[u] + heuristic(ui, uj) + 1e-9) continue;
    if (done(ui, uj) && !blocked[u]) {
      reached = u;
      break;
    }
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int vi = ui + di;
        const int vj = uj + dj;
        if ((di == 0 && dj == 0) || vi < 0 || vj < 0 || vi >= w || vj >= h || blocked[index(vi, vj)]) continue;
        const double c = cost[u] + kCellMm * std::hypot(di, dj);
        if (c < cost[index(vi, vj)]) {
          cost[index(vi, vj)] = c;
          parent[index(vi, vj)] = u;
          open.emplace(c + heuristic(vi, vj), index(vi, vj));
        }
      }
    }
  }
  if (!reached) return std::nullopt;
  std::vector<Vector2d> cells;
  for (std::size_t v = *reached; v != blocked.size(); v = parent[v]) {
    cells.push_back(at(static_cast<int>(v % w), static_cast<int>(v / w)));
  }
  std::reverse(cells.begin(), cells.end());
  cells.front() = from;
  // Straighten: from each kept point, the farthest later one in clear straight sight.
  std::vector<Vector2d> route{cells.front()};
  std::size_t i = 0;
  while (i + 1 < cells.size()) {
    std::size_t j = cells.size() - 1;
    while (j > i + 1 && !segment_clear(world, cells[i], cells[j], required)) --j;
    route.push_back(cells[j]);
    i = j;
  }
  return route;
}

std::optional<std::vector<Vector2d>> teach_detour(const sim::World& world, const Vector2d& from, std::uint32_t goal,
                                                  double clearance_mm, double end_mm, double side) {
  const Vector2d g = world.objects.at(goal);
  const Vector2d d = g - from;
  const Vector2d normal(-d.y(), d.x());
  const Vector2d corner = (from + 0.5 * d + 0.4 * side * normal).cwiseMax(Vector2d::Zero()).cwiseMin(world.size);
  auto first = teach_route_to(world, from, corner, clearance_mm, 0, 12);
  if (!first) return std::nullopt;
  auto second = teach_route(world, first->back(), goal, clearance_mm, end_mm);
  if (!second) return std::nullopt;
  first->insert(first->end(), second->begin() + 1, second->end());
  return first;
}

std::vector<Vector2d> sample_route(const std::vector<Vector2d>& route, double spacing_mm) {
  std::vector<Vector2d> out;
  if (route.empty()) return out;
  out.push_back(route.front());
  double carried = 0;  // distance since the last sample
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Vector2d& a = route[k - 1];
    const Vector2d d = route[k] - a;
    const double len = d.norm();
    double t = spacing_mm - carried;
    while (t <= len) {
      out.emplace_back(a + d * (t / len));
      t += spacing_mm;
    }
    carried = len - (t - spacing_mm);
  }
  if ((out.back() - route.back()).norm() > 1e-9) out.push_back(route.back());
  return out;
}

double route_length(const std::vector<Vector2d>& route) {
  double total = 0;
  for (std::size_t k = 1; k < route.size(); ++k) total += (route[k] - route[k - 1]).norm();
  return total;
}

double route_turning(const std::vector<Vector2d>& route) {
  double total = 0;
  std::optional<Vector2d> previous;
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Vector2d d = route[k] - route[k - 1];
    if (d.norm() < 1e-6) continue;
    if (previous) {
      total += std::abs(std::atan2(previous->x() * d.y() - previous->y() * d.x(), previous->dot(d)));
    }
    previous = d;
  }
  return total;
}

std::vector<nav::qualnav::Viewframe> record_viewpath(const sim::World& world, const std::vector<Vector2d>& points,
                                                     const QualnavSensing& sensing, std::uint64_t seed) {
  sim::Random bearing_noise(seed);
  sim::Random range_noise(seed ^ 0x9E3779B97F4A7C15ULL);
  sim::Random compass_noise(seed ^ 0xC2B2AE3D27D4EB4FULL);
  sim::PanoramaSettings panorama;
  panorama.bearing_noise_deg = sensing.bearing_noise_deg;
  nav::PanoramaReader reader(nav::PanoramaModel{world.marble_diameter / 2, sensing.bearing_noise_deg});
  std::vector<nav::qualnav::Viewframe> out;
  out.reserve(points.size());
  for (const Vector2d& p : points) {
    const sim::Ring ring = sim::render_ring(world, sim::Pose2{p.x(), p.y(), 0}, panorama, &bearing_noise);
    std::vector<nav::PanoramaSighting> sightings = reader.read(ring.image);
    apply_range_error(sightings, sensing.range_error, [&] { return range_noise.uniform(); });
    const double compass = std::fmod(compass_noise.normal(0, panorama.compass_sigma_deg) + 360, 360);
    out.push_back(
        nav::qualnav::viewframe_from_sightings(sightings, compass, qualnav_interval_factor(sensing.range_error)));
  }
  return out;
}

double qualnav_interval_factor(double range_error) {
  return 1 + range_error + kRangeEstimateSlack;
}

}  // namespace neopipe::rig
