#pragma once
// Path planning over the context-based graph (park-kender.md §5): nodes are placements
// (object, corner) plus whatever virtual nodes the caller adds; an edge is one custom-map step with
// its window travel D, unreliability U = -log R and landmark-based distance L (the straight line
// between the two landmarks, whatever corners they are held at). Four criteria: shortest (min D),
// most reliable (min U), the compromise min D/R = D * e^U, which is not additive along a path and is
// found exactly among the vertices of the convex hull of the paths' (D, U) points (planner.cpp says
// why), and the landmark-based shortest (min L), the paper's foil for context-based planning.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace neopipe::nav::mapmaker {

enum class CostCriterion : std::uint8_t { distance, reliability, ratio, landmark };
/// Every criterion, for option lists and parsing: a new criterion is added here once.
inline constexpr std::array kCriteria{CostCriterion::distance, CostCriterion::reliability, CostCriterion::ratio,
                                      CostCriterion::landmark};

/// "distance", "reliability", "ratio", "landmark"; parse_criterion accepts exactly these and nothing else.
std::string_view criterion_name(CostCriterion c);
std::optional<CostCriterion> parse_criterion(std::string_view text);

struct PlanEdge {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  double distance = 0;           ///< D >= 0, mm of window travel
  double unreliability = 0;      ///< U = -log R >= 0
  double landmark_distance = 0;  ///< L >= 0, mm between the two landmarks
};

/// A directed graph with nonnegative (D, U, L) edge costs. Edges keep their insertion index, which is
/// how a path names them and how ties are broken: the caller inserts preferred edges first.
/// The out-edge index is built lazily by the first query after an add_edge, so a graph shared
/// between threads must be queried once (out_edges or plan_path) before it is shared.
class PlanGraph {
 public:
  /// Throws std::length_error when `nodes` does not fit a 32-bit node id.
  explicit PlanGraph(std::size_t nodes);

  std::size_t node_count() const { return first_out_.size() - 1; }
  const std::vector<PlanEdge>& edges() const { return edges_; }

  /// Returns the edge's index. Throws std::invalid_argument for a node out of range or a negative
  /// or non-finite cost; the message names the edge.
  std::uint32_t add_edge(const PlanEdge& edge);

  /// Indices of the edges leaving `node`, in insertion order. Valid after the last add_edge.
  std::span<const std::uint32_t> out_edges(std::uint32_t node) const;

  /// mm added to every path's D in the compromise criterion, which then minimises (D + offset) e^U:
  /// with 0 (the default, the paper's D / R) a path of D = 0 costs 0 whatever its U. Throws
  /// std::invalid_argument unless finite and >= 0.
  void set_ratio_offset(double offset);
  double ratio_offset() const { return ratio_offset_; }

 private:
  void index() const;
  std::vector<PlanEdge> edges_;
  mutable std::vector<std::uint32_t> first_out_;
  mutable std::vector<std::uint32_t> out_;
  mutable bool indexed_ = false;
  double ratio_offset_ = 0;
};

struct PlannedPath {
  std::vector<std::uint32_t> edges;  ///< edge indices, source to target
  double distance = 0;               ///< sum of D, added source to target
  double unreliability = 0;          ///< sum of U, added source to target
  double landmark_distance = 0;      ///< sum of L, added source to target
  double ratio() const;              ///< D / R = D * exp(U); 0 when D is 0, whatever U
};

/// What a search did, for benchmarks and for checking that memory follows the work done.
struct PlanStats {
  std::size_t labels_created = 0;  ///< heap entries: improved nodes, over all Dijkstra runs
  std::size_t labels_settled = 0;  ///< nodes settled, over all Dijkstra runs
  std::size_t searches = 0;        ///< Dijkstra runs (ratio: 2 + one per segment of the hull tried)
};

/// The best path from any node of `sources` (starting at cost 0) to any node of `targets` under
/// `criterion`; nullopt when no target is reachable (or either set is empty). A source that is
/// also a target gives the empty path. Throws std::invalid_argument for a source or target out of
/// range.
///
/// Determinism and ties: distance compares (D, then U), reliability compares (U, then D), landmark
/// compares (L, then D, then U), ratio compares (D e^U, then D, then U) among the hull's vertices,
/// each found by a Dijkstra run on wd D + wu U (then D); a path is replaced only by a strictly better
/// one; nodes are settled in order of (cost, node id) and edges relaxed in insertion order. So the
/// same graph always gives the same path. Among equal paths, the one that reaches each node first in
/// that order wins: between parallel edges, or edges leaving the same node, the earlier-inserted one;
/// between different predecessors of equal cost, the one with the smaller node id (settled first);
/// between targets of equal cost, the smaller node id.
///
/// Cost: distance, reliability and landmark are Dijkstra, O(E log V). Ratio is 2 + h Dijkstra runs
/// for h vertices on the lower-left convex hull of (D, U) (a handful in practice), O(V + E) memory.
std::optional<PlannedPath> plan_path(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                     std::span<const std::uint32_t> targets, CostCriterion criterion);
std::optional<PlannedPath> plan_path(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                     std::span<const std::uint32_t> targets, CostCriterion criterion, PlanStats& stats);

}  // namespace neopipe::nav::mapmaker
