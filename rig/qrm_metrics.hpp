#pragma once
// The metrics of QRM map building (spec qrm.md §10), judged against ground truth: the rig knows the
// marbles' true positions, the map does not. Over the C(N,3) triples of a landmark set, three
// relations each (ij:k, jk:i, ki:j):
//   M1 = 100 * sum(20 - |S|) / (19 * 3 * C(N,3))   incorrect states removed (%)
//   M2 = % triples whose three relations are all single states
//   M3 = sum of c_ij over the RNG candidates (the pairs not pruned, spec §8)
//   M4 = % of the open non-true states that are not adjacent to the true state (spec §2 adjacency)
//   M5 = time per update (the caller times it; see QrmImageReport)
// and the estimated RNG (its pairs not pruned, and its certain edges, c_ij = 0) against the true
// RNG.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "nav/qrm/relational_map.hpp"
#include "nav/qrm/rng.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

using RngEdges = std::vector<std::pair<std::size_t, std::size_t>>;

/// An estimated RNG against the true one (edges i < j).
struct RngComparison {
  std::size_t estimated = 0;  ///< edges of the estimate
  std::size_t truth = 0;      ///< edges of the true RNG
  std::size_t common = 0;     ///< in both
  double precision = 1;       ///< common / estimated (1 for an empty estimate)
  double recall = 1;          ///< common / truth (1 for an empty truth)
  bool equal = false;
};

RngComparison compare_rng(const RngEdges& estimated, const RngEdges& truth);

struct QrmMetrics {
  std::size_t landmarks = 0;   ///< N
  std::size_t triples = 0;     ///< C(N,3)
  double m1 = 0;               ///< % incorrect states removed
  double m2 = 0;               ///< % triples fully resolved
  double m3 = 0;               ///< sum of c_ij over the RNG candidates
  double m4 = 0;               ///< % open non-true states not adjacent to the truth (0 when none is open)
  std::size_t open_wrong = 0;  ///< open non-true states (M4's denominator)
  std::size_t lost = 0;        ///< relations that no longer hold their true state (0 unless the map is wrong)
  RngEdges rng;                ///< candidates not pruned (i < j, sorted): the estimated RNG
  RngEdges certain_rng;        ///< of them, those with c_ij = 0
  RngComparison versus_truth;  ///< rng against the true RNG
  RngComparison certain_versus_truth;
};

/// The metrics of `map` over the landmarks `landmarks` (ids into `truth`; by default every id of
/// `truth`, landmarks absent from the map counting as relations of all 20 states). `true_rng`: the
/// RNG of `truth` (computed when absent). Throws nav::qrm::DegenerateTripleError for a degenerate
/// true triple, std::out_of_range for a landmark id beyond `truth`.
QrmMetrics qrm_metrics(const nav::qrm::RelationalMap& map, std::span<const Eigen::Vector2d> truth,
                       const std::optional<RngEdges>& true_rng = std::nullopt);

/// The first degenerate triple (i < j < k) of a world (spec §2: some e within 1e-9 |AB|^2 of zero
/// for one of its orders), or none. The simulator resamples such worlds; a user's file is an error.
std::optional<std::array<std::size_t, 3>> first_degenerate_triple(std::span<const Eigen::Vector2d> points);

/// generate_world(request), redrawn with the next seed (request.seed + 1, + 2, ...) while it holds a
/// degenerate triple (spec §2). Throws sim::WorldError as generate_world does, or after 1000 draws.
sim::World generate_qrm_world(sim::WorldRequest request);

}  // namespace neopipe::rig
