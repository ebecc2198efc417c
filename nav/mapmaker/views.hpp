#pragma once
// Every placement the navigator can be in, (object, corner), and what it sees there: the objects in
// its window and the obvious and isolated landmarks among them. Computed once per world; parkways,
// trajectories, QOC and the planner all read it.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "nav/common/landmarks.hpp"
#include "nav/common/window.hpp"
#include "nav/mapmaker/object_grid.hpp"
#include "nav/mapmaker/workspace.hpp"

namespace neopipe::nav::mapmaker {

/// The navigator holding `object` at `corner`.
struct Placement {
  std::uint32_t object = 0;
  Corner corner = Corner::SW;

  /// Node id in the context-based graph: 4 object + corner.
  std::uint32_t node() const { return 4 * object + static_cast<std::uint32_t>(index(corner)); }
  static Placement of_node(std::uint32_t node) { return {node / 4, kCorners[node % 4]}; }
  friend bool operator==(const Placement&, const Placement&) = default;
};

struct QocRange {
  int low = 0;
  int high = 0;
  bool contains(int q) const { return low <= q && q <= high; }
  bool overlaps(const QocRange& o) const { return low <= o.high && o.low <= high; }
};

class WorldViews {
 public:
  /// Keeps a pointer to `workspace`, which must outlive the views: a temporary cannot be given
  /// (`WorldViews(workspace_of(world), ...)` read a dead stack frame, found by ASan: issue 18).
  WorldViews(const Workspace& workspace, const WindowModel& window);
  WorldViews(const Workspace&& workspace, const WindowModel& window) = delete;

  const Workspace& workspace() const { return *workspace_; }
  const WindowModel& window() const { return window_; }
  const ObjectGrid& grid() const { return grid_; }
  std::size_t object_count() const { return workspace_->objects.size(); }
  const Eigen::Vector2d& position(std::uint32_t object) const { return workspace_->objects[object]; }

  /// Lower-left corner of the window at `p`.
  Eigen::Vector2d origin(const Placement& p) const { return window_.origin(position(p.object), p.corner); }

  /// Ids in view at `p`, ascending; the reference itself included.
  std::span<const std::uint32_t> visible(const Placement& p) const;

  /// What `description` selects at `p` (the function the navigator runs), as an object id.
  std::optional<std::uint32_t> landmark(const Placement& p, Description description) const;
  std::optional<std::uint32_t> obvious(const Placement& p) const { return landmark(p, Description::Obvious); }
  std::optional<std::uint32_t> isolated(const Placement& p) const { return landmark(p, Description::Isol); }

  /// Quadrant occupancy of `object` (paper §6.3.1): occupied[q] when another object is in view with
  /// the object held at opposite(q), i.e. in its quadrant q. Indexed by Corner (SE, SW, NE, NW).
  std::array<bool, 4> quadrants(std::uint32_t object) const;
  /// QOC: the number of occupied quadrants, 0..4.
  int qoc(std::uint32_t object) const;
  /// The QOCs a navigator could measure when positions may be off by up to `tolerance` mm across a
  /// window border: low counts the quadrants with an object deeper than that inside, high those with
  /// an object anywhere within that of the window. low <= qoc <= high; both are qoc at tolerance 0.
  QocRange qoc_range(std::uint32_t object, double tolerance) const;
  /// Which quadrants hold an object, each `unsure` when its objects all lie within `tolerance` of
  /// the window's border (inside or out): the pattern qoc_range counts.
  QuadrantPattern quadrant_pattern(std::uint32_t object, double tolerance) const;

 private:
  const Workspace* workspace_;
  WindowModel window_;
  ObjectGrid grid_;
  std::vector<std::uint32_t> first_;  // CSR over placements (node ids)
  std::vector<std::uint32_t> seen_;
  std::vector<std::int64_t> isolated_;  // per node: object id or -1
};

/// The ids `p`'s view holds, with positions, in the form the shared descriptors take.
struct GatheredView {
  std::vector<Eigen::Vector2d> points;
  std::size_t reference = 0;
  View view() const { return {points, reference}; }
};
GatheredView gather(const WorldViews& views, const Placement& p);

}  // namespace neopipe::nav::mapmaker
