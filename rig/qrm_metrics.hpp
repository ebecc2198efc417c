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
#include <array>
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

/// The ground truth of a landmark set, computed once so that a map can be judged after every image:
/// the true state of the three relations of every triple, and the true RNG.
class QrmTruth {
 public:
  /// Throws nav::qrm::DegenerateTripleError for a degenerate triple.
  explicit QrmTruth(std::span<const Eigen::Vector2d> points);
  [[nodiscard]] std::size_t landmarks() const { return n_; }
  [[nodiscard]] const RngEdges& rng() const { return rng_; }
  /// The metrics of `map` over every landmark of the truth (landmarks absent from the map count as
  /// relations of all 20 states). Throws std::out_of_range for a map landmark beyond the truth.
  [[nodiscard]] QrmMetrics metrics(const nav::qrm::RelationalMap& map) const;

 private:
  std::size_t n_ = 0;
  /// ij:k, jk:i, ki:j of every triple i < j < k, in lexicographic order.
  std::vector<std::array<nav::qrm::State, 3>> states_;
  RngEdges rng_;
};

/// QrmTruth(truth).metrics(map).
QrmMetrics qrm_metrics(const nav::qrm::RelationalMap& map, std::span<const Eigen::Vector2d> truth);

/// generate_world(request), redrawn with the next seed (request.seed + 1, + 2, ...) while it holds a
/// degenerate triple (spec §2). Throws sim::WorldError as generate_world does, or after 1000 draws.
sim::World generate_qrm_world(sim::WorldRequest request);

}  // namespace neopipe::rig
