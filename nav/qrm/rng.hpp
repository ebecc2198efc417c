#pragma once
// The relative neighbourhood graph (spec qrm.md §8): estimated from a map (edge costs, pruning),
// exactly from positions (through the EDC classifier, or by distances), and routes over it.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "nav/qrm/relational_map.hpp"

namespace neopipe::nav::qrm {

/// An RNG candidate (i < j) of a map and its cost c_ij = sum_k f_k / N, f_k = |ij:k & lune| / |ij:k|.
struct RngEdge {
  LandmarkId i = 0;
  LandmarkId j = 0;
  double cost = 0;
  /// cost * unit exactly (RngEstimate::unit): costs compare and add without rounding, so Dijkstra's
  /// ties are real ties.
  std::int64_t scaled_cost = 0;
};

struct RngEstimate {
  std::vector<RngEdge> edges;  ///< not pruned, sorted by (i, j)
  std::int64_t unit = 1;       ///< N * lcm(1..20): a cost of 1 in scaled_cost
};

/// c_ij from the relations ij:k of every other landmark k in a map of `landmarks` landmarks; none
/// when some ij:k lies wholly in the lune (the edge is pruned).
std::optional<double> rng_edge_cost(std::span<const StateSet> relations, std::size_t landmarks);

/// The cost of (i, j), or none when some ij:k lies wholly in the lune (pruned).
std::optional<RngEdge> rng_edge(const RelationalMap& map, LandmarkId i, LandmarkId j);
/// Every pair of the map's landmarks that is not pruned.
RngEstimate estimate_rng(const RelationalMap& map);

/// Three positions whose EDC state is degenerate (spec §2's rule).
class DegenerateTripleError : public std::runtime_error {
 public:
  DegenerateTripleError(std::size_t i, std::size_t j, std::size_t k);
  std::size_t i;
  std::size_t j;
  std::size_t k;
};

/// The RNG of exact positions through the classifier: (i, j), i < j, when no k has ij:k in the lune.
/// Throws DegenerateTripleError for the first degenerate ij:k met.
std::vector<std::pair<std::size_t, std::size_t>> true_rng(std::span<const Eigen::Vector2d> points);

/// The RNG by distances: (i, j) when no k has max(|ik|, |jk|) < |ij|. A reference for tests.
std::vector<std::pair<std::size_t, std::size_t>> rng_by_distances(std::span<const Eigen::Vector2d> points);

/// The cheapest path from `from` to `to` over `rng` with edge weight 1 + c_ij; among equally cheap
/// paths the lexicographically smallest id sequence. Empty when `to` cannot be reached.
std::vector<LandmarkId> plan_route(const RngEstimate& rng, LandmarkId from, LandmarkId to);

}  // namespace neopipe::nav::qrm
