#include "nav/mapmaker/views.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace neopipe::nav::mapmaker {
namespace {

const WindowModel& checked(const WindowModel& w) {
  // The reference must be strictly inside its own window, and a window must have room beyond it.
  if (!(std::isfinite(w.side) && w.side > 0)) throw MapError(fmt::format("window side {} mm must be positive", w.side));
  if (!(w.margin > 0 && w.margin < w.side / 2)) {
    throw MapError(
        fmt::format("window margin {} mm must lie strictly between 0 and half the side ({} mm)", w.margin, w.side / 2));
  }
  return w;
}

}  // namespace

WorldViews::WorldViews(const Workspace& workspace, const WindowModel& window)
    : workspace_(&workspace), window_(checked(window)), grid_(workspace.objects, window.side) {
  const std::size_t nodes = 4 * workspace.objects.size();
  first_.reserve(nodes + 1);
  first_.push_back(0);
  std::vector<std::uint32_t> in_view;
  for (std::uint32_t node = 0; node < nodes; ++node) {
    const Placement p = Placement::of_node(node);
    const Eigen::Vector2d lo = origin(p);
    in_view.clear();
    grid_.query(lo, lo + Eigen::Vector2d(window.side, window.side), in_view);
    seen_.insert(seen_.end(), in_view.begin(), in_view.end());
    first_.push_back(static_cast<std::uint32_t>(seen_.size()));
  }
  isolated_.resize(nodes, -1);
  for (std::uint32_t node = 0; node < nodes; ++node) {
    const Placement p = Placement::of_node(node);
    const GatheredView g = gather(*this, p);
    if (const auto chosen = isolated_landmark(g.view())) isolated_[node] = visible(p)[*chosen];
  }
}

std::span<const std::uint32_t> WorldViews::visible(const Placement& p) const {
  const std::uint32_t node = p.node();
  return {seen_.data() + first_[node], first_[node + 1] - first_[node]};
}

std::optional<std::uint32_t> WorldViews::landmark(const Placement& p, Description description) const {
  if (description == Description::Isol) {
    const std::int64_t id = isolated_[p.node()];
    return id < 0 ? std::nullopt : std::optional<std::uint32_t>(static_cast<std::uint32_t>(id));
  }
  const GatheredView g = gather(*this, p);
  const auto chosen = select_landmark(description, g.view());
  return chosen ? std::optional<std::uint32_t>(visible(p)[*chosen]) : std::nullopt;
}

std::array<bool, 4> WorldViews::quadrants(std::uint32_t object) const {
  std::array<bool, 4> occupied{};
  for (const Corner q : kCorners) occupied[index(q)] = visible({object, opposite(q)}).size() > 1;
  return occupied;
}

int WorldViews::qoc(std::uint32_t object) const {
  const std::array<bool, 4> q = quadrants(object);
  return static_cast<int>(std::count(q.begin(), q.end(), true));
}

QocRange WorldViews::qoc_range(std::uint32_t object, double tolerance) const {
  if (tolerance <= 0) {
    const int q = qoc(object);
    return {q, q};
  }
  QocRange r;
  for (const Occupancy o : quadrant_pattern(object, tolerance)) {
    r.low += o == Occupancy::occupied;
    r.high += o != Occupancy::empty;
  }
  return r;
}

QuadrantPattern WorldViews::quadrant_pattern(std::uint32_t object, double tolerance) const {
  QuadrantPattern pattern{};
  if (tolerance <= 0) {
    const std::array<bool, 4> q = quadrants(object);
    for (std::size_t i = 0; i < q.size(); ++i) pattern[i] = q[i] ? Occupancy::occupied : Occupancy::empty;
    return pattern;
  }
  const Eigen::Vector2d t(tolerance, tolerance);
  for (const Corner held : kCorners) {
    const Eigen::Vector2d lo = origin({object, held});
    const Eigen::Vector2d hi = lo + Eigen::Vector2d(window_.side, window_.side);
    bool surely = false;
    bool maybe = false;
    grid_.for_each_near(lo - t, hi + t, [&](std::uint32_t id) {
      if (id == object) return;
      const Eigen::Vector2d& p = position(id);
      const double depth = std::min({p.x() - lo.x(), p.y() - lo.y(), hi.x() - p.x(), hi.y() - p.y()});
      surely = surely || depth > tolerance;
      maybe = maybe || depth > -tolerance;
    });
    // Held at `held`, the window looks into the opposite quadrant.
    pattern[static_cast<std::size_t>(index(opposite(held)))] =
        surely ? Occupancy::occupied : (maybe ? Occupancy::unsure : Occupancy::empty);
  }
  return pattern;
}

GatheredView gather(const WorldViews& views, const Placement& p) {
  GatheredView g;
  const std::span<const std::uint32_t> ids = views.visible(p);
  g.points.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] == p.object) g.reference = i;
    g.points.push_back(views.position(ids[i]));
  }
  return g;
}

}  // namespace neopipe::nav::mapmaker
