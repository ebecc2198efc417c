#pragma once
// Path planning over the context-based graph (park-kender.md §5): nodes are placements
// (object, corner) plus whatever virtual nodes the caller adds; an edge is one custom-map step with
// its window travel D and unreliability U = -log R. Three criteria: shortest (min D), most reliable
// (min U) and the compromise min D/R = D * e^U, found exactly by bi-criteria labels because D/R is
// not additive along a path.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace neopipe::nav::mapmaker {

enum class CostCriterion : std::uint8_t { distance, reliability, ratio };

std::string_view criterion_name(CostCriterion c);
std::optional<CostCriterion> parse_criterion(std::string_view text);

struct PlanEdge {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  double distance = 0;       ///< D >= 0, mm of window travel
  double unreliability = 0;  ///< U = -log R >= 0
};

/// A directed graph with nonnegative (D, U) edge costs. Edges keep their insertion index, which is
/// how a path names them and how ties are broken: the caller inserts preferred edges first.
class PlanGraph {
 public:
  explicit PlanGraph(std::size_t nodes);

  std::size_t node_count() const { return first_out_.size() - 1; }
  const std::vector<PlanEdge>& edges() const { return edges_; }

  /// Returns the edge's index. Throws std::invalid_argument for a node out of range or a negative
  /// or non-finite cost.
  std::uint32_t add_edge(const PlanEdge& edge);

  /// Indices of the edges leaving `node`, in insertion order. Valid after the last add_edge.
  std::span<const std::uint32_t> out_edges(std::uint32_t node) const;

 private:
  void index() const;
  std::vector<PlanEdge> edges_;
  mutable std::vector<std::uint32_t> first_out_;
  mutable std::vector<std::uint32_t> out_;
  mutable bool indexed_ = false;
};

struct PlannedPath {
  std::vector<std::uint32_t> edges;  ///< edge indices, source to target
  double distance = 0;               ///< sum of D
  double unreliability = 0;          ///< sum of U
  double ratio() const;              ///< D / R = D * exp(U)
};

/// The best path from any node of `sources` (starting at cost 0) to any node of `targets` under
/// `criterion`; nullopt when no target is reachable. A source that is also a target gives the
/// empty path.
///
/// Determinism and ties: distance compares (D, then U), reliability compares (U, then D), ratio
/// compares (D e^U, then D, then U); a path is replaced only by a strictly better one; nodes are
/// settled in order of (cost, node id) and edges relaxed in insertion order. So the same graph
/// always gives the same path, and among equal paths the one using earlier-inserted edges wins.
std::optional<PlannedPath> plan_path(const PlanGraph& graph, std::span<const std::uint32_t> sources,
                                     std::span<const std::uint32_t> targets, CostCriterion criterion);

}  // namespace neopipe::nav::mapmaker
