#include "nav/qrm/navigator/local_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <utility>

namespace neopipe::nav::qrm {
namespace {

using Eigen::Vector2d;

// The grid reaches this far beyond the target (mm), and at least this far around the tool, at most
// the panoramic sensor's range: room to go round a cluster of marbles, bounded work.
constexpr double kBeyondTargetMm = 80;
constexpr double kLeastHalfSideMm = 100;
constexpr double kMostHalfSideMm = 600;

}  // namespace

bool step_allowed(const std::vector<Obstacle>& obstacles, const Vector2d& p, double keep) {
  return std::all_of(obstacles.begin(), obstacles.end(), [&](const Obstacle& o) {
    const double after = (p - o.at).norm();
    return after >= keep || after >= o.at.norm();
  });
}

double cell_advantage(const std::vector<Obstacle>& obstacles, LandmarkId target, const Vector2d& target_at,
                      const Vector2d& p) {
  // The Dijkstra of path_step asks this for every cell it pops, over every marble in view: one
  // square root for the nearest instead of one per marble. Exact: norm() is the square root of
  // squaredNorm(), and a correctly rounded square root is monotone, so it keeps the minimum.
  double other = std::numeric_limits<double>::infinity();
  for (const Obstacle& o : obstacles) {
    if (o.id != target) other = std::min(other, (p - o.at).squaredNorm());
  }
  return std::sqrt(other) - (p - target_at).norm();
}

std::optional<Vector2d> path_step(const std::vector<Obstacle>& obstacles, LandmarkId target, const Vector2d& target_at,
                                  double step, double keep, double margin, double cell) {
  const double half = std::clamp(target_at.norm() + kBeyondTargetMm, kLeastHalfSideMm, kMostHalfSideMm);
  const int n = 2 * static_cast<int>(std::ceil(half / cell)) + 1;
  const int mid = n / 2;
  const auto index = [n](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x);
  };
  const auto centre = [&](int x, int y) { return Vector2d((x - mid) * cell, (y - mid) * cell); };
  // Blocked cells: each marble's disc of `keep`, shrunk to the tool's distance when an arm error has
  // taken it inside one (it may not come closer, as step_allowed says).
  std::vector<std::uint8_t> blocked(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0);
  std::vector<double> radii;
  radii.reserve(obstacles.size());
  for (const Obstacle& o : obstacles) {
    const double r = std::min(keep, o.at.norm()) - 1e-9;
    radii.push_back(r);
    if (r <= 0) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor((o.at.x() - r) / cell)) + mid);
    const int x1 = std::min(n - 1, static_cast<int>(std::ceil((o.at.x() + r) / cell)) + mid);
    const int y0 = std::max(0, static_cast<int>(std::floor((o.at.y() - r) / cell)) + mid);
    const int y1 = std::min(n - 1, static_cast<int>(std::ceil((o.at.y() + r) / cell)) + mid);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        if ((centre(x, y) - o.at).norm() < r) blocked[index(x, y)] = 1;
      }
    }
  }
  // Dijkstra from the tool's cell; the first cell popped inside the target's cell ends it.
  std::vector<double> dist(blocked.size(), std::numeric_limits<double>::infinity());
  std::vector<std::int32_t> parent(blocked.size(), -1);
  using Item = std::pair<double, std::int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const auto start = static_cast<std::int32_t>(index(mid, mid));
  dist[static_cast<std::size_t>(start)] = 0;
  open.emplace(0, start);
  std::int32_t goal = -1;
  constexpr std::array<std::pair<int, int>, 8> kMoves{
      {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
  while (!open.empty()) {
    const auto [d, c] = open.top();
    open.pop();
    const auto uc = static_cast<std::size_t>(c);
    if (d > dist[uc]) continue;
    const int x = c % n;
    const int y = c / n;
    if (cell_advantage(obstacles, target, target_at, centre(x, y)) >= margin) {
      goal = c;
      break;
    }
    for (const auto& [dx, dy] : kMoves) {
      const int nx = x + dx;
      const int ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= n || ny >= n) continue;
      const std::size_t u = index(nx, ny);
      if (blocked[u] != 0) continue;
      const double nd = d + ((dx != 0 && dy != 0) ? std::numbers::sqrt2 : 1.0);
      if (nd < dist[u]) {
        dist[u] = nd;
        parent[u] = c;
        open.emplace(nd, static_cast<std::int32_t>(u));
      }
    }
  }
  if (goal < 0 || goal == start) return std::nullopt;
  // Aim at the farthest point of the path in sight of the tool (the straight segment to it crosses
  // no blocked cell), so the steps follow the path's shortcut rather than the grid's 45° zigzag.
  std::vector<std::int32_t> path;
  for (std::int32_t c = goal; c != -1; c = parent[static_cast<std::size_t>(c)]) path.push_back(c);
  std::reverse(path.begin(), path.end());
  // Exactly, not by cells: a segment between blocked cells' centres may still graze a disc.
  const auto in_sight = [&](const Vector2d& p) {
    const int samples = static_cast<int>(std::ceil(p.norm() / (cell / 4)));
    for (int i = 1; i <= samples; ++i) {
      const Vector2d s = p * (static_cast<double>(i) / samples);
      for (std::size_t m = 0; m < obstacles.size(); ++m) {
        if ((s - obstacles[m].at).norm() < radii[m]) return false;
      }
    }
    return true;
  };
  std::optional<Vector2d> best;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Vector2d p = centre(path[i] % n, path[i] / n);
    if (!in_sight(p)) break;
    if (const Vector2d s = step * p.normalized(); in_sight(s)) best = s;
  }
  return best;
}

}  // namespace neopipe::nav::qrm
