#pragma once
// The visual memory (qualnav.md §7; seed 003 §3): viewpaths — viewframes recorded every 20 mm along
// routes — and the links between them, searched by A*.
//
// Consecutive viewframes of a viewpath are linked. Decision: viewframes of different viewpaths are
// linked when they share ≥ 2 landmarks and their viewframe heading is ≤ 150 mm. Edge cost = heading
// length; heuristic = heading length to the goal when a pair is shared with it, else 0. Heading
// lengths are estimates, so the heuristic is not guaranteed admissible: A* returns the path it
// finds first with closed nodes never reopened (a plan, re-made after every step, not a proof).

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "nav/qualnav/metric/viewframe.hpp"
#include "nav/qualnav/metric/viewframe_heading.hpp"

namespace neopipe::nav::qualnav {

inline constexpr double kViewpathSpacingMm = 20;  ///< Decision: a viewframe every 20 mm
inline constexpr double kLinkDistanceMm = 150;    ///< Decision: cross-viewpath links

struct MemoryLink {
  std::size_t to = 0;
  double cost = 0;  ///< heading length, mm
};

struct MemoryNode {
  std::size_t viewpath = 0;
  std::size_t index = 0;  ///< along its viewpath
  Viewframe view;
};

class VisualMemory {
 public:
  /// Appends a viewpath (its viewframes in travel order) and links it. Returns its index.
  std::size_t add_viewpath(const std::vector<Viewframe>& viewframes);

  [[nodiscard]] const std::vector<MemoryNode>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<std::vector<MemoryLink>>& links() const { return links_; }
  [[nodiscard]] std::size_t viewpaths() const { return viewpaths_; }
  /// The frame scales over every remembered viewframe.
  [[nodiscard]] const FrameScales& scales() const { return scales_; }
  [[nodiscard]] const LocalizationOptions& localization() const { return options_; }
  void set_localization(const LocalizationOptions& options) { options_ = options; }

 private:
  std::vector<MemoryNode> nodes_;
  std::vector<std::vector<MemoryLink>> links_;
  std::size_t viewpaths_ = 0;
  FrameScales scales_;
  LocalizationOptions options_;
};

/// A* over a graph given as adjacency lists: the node ids from `start` to `goal`, both included;
/// empty when the goal cannot be reached. `heuristic(n)` estimates the cost from n to the goal.
/// Ties by lower node id.
std::vector<std::size_t> astar(const std::vector<std::vector<MemoryLink>>& graph, std::size_t start, std::size_t goal,
                               const std::function<double(std::size_t)>& heuristic);

/// The plan over `memory` from `start` to `goal` with the spec's heuristic (heading length to the
/// goal node when the two share a pair, else 0).
std::vector<std::size_t> plan_over_memory(const VisualMemory& memory, std::size_t start, std::size_t goal);

/// The length of a node path by its links (0 for fewer than two nodes; infinity if unlinked).
double path_cost(const std::vector<std::vector<MemoryLink>>& graph, const std::vector<std::size_t>& path);

}  // namespace neopipe::nav::qualnav
