#pragma once
// The arrangement of all LPB lines of n landmarks (spec qualnav.md §4): its lines, its crossings
// with their multiplicities m_p, the region count R = 1 + N + Σ(m_p − 1), and the orientation
// regions themselves, each a cell named by its sign vector over every pair, with a point inside it,
// and their adjacency (differ in one LPB and share a boundary segment).
//
// The cells are found without the count formula: a point in every angular wedge round every
// crossing (each cell of a line arrangement with a crossing has one at a corner), deduplicated by
// sign vector. The edges (the pieces of each line between consecutive crossings) give the
// adjacency, and Euler's formula over them a third count.

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "nav/qualnav/topology/lpb.hpp"

namespace neopipe::nav::qualnav {

/// LPB(L1, L2) as a line: through L1, towards L2.
struct LpbLine {
  LandmarkPair pair;
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< L1
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< L2
};

/// A point where m_p >= 2 LPB lines meet.
struct LineCrossing {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  std::vector<std::size_t> lines;      ///< indices into Arrangement::lines(), increasing
  std::optional<LandmarkId> landmark;  ///< set when the crossing is a landmark (its n − 1 lines)
  [[nodiscard]] std::size_t multiplicity() const { return lines.size(); }
};

class Arrangement {
 public:
  /// The LPB lines of the landmarks `ids` at `positions` (same length). std::invalid_argument with a
  /// one-line message naming the landmarks for fewer than two, two that coincide, three that are
  /// collinear (their LPB lines coincide), or ids repeated.
  Arrangement(std::span<const LandmarkId> ids, std::span<const Eigen::Vector2d> positions);

  [[nodiscard]] std::span<const LandmarkId> ids() const { return ids_; }
  [[nodiscard]] std::span<const Eigen::Vector2d> positions() const { return positions_; }
  /// One line per pair (i, j), i before j in ids(), in all_pairs() order.
  [[nodiscard]] std::span<const LpbLine> lines() const { return lines_; }
  [[nodiscard]] std::span<const LandmarkPair> pairs() const { return pairs_; }
  /// Landmarks first (in ids() order), then the other crossings ordered by x, then y.
  [[nodiscard]] std::span<const LineCrossing> crossings() const { return crossings_; }

  /// R = 1 + N + Σ(m_p − 1).
  [[nodiscard]] std::size_t region_count() const;

  /// The sign vector of `point` over pairs() (0 on a line, within `tolerance` as a sine).
  [[nodiscard]] SignVector signs_at(const Eigen::Vector2d& point, double tolerance = 0.0) const;

  /// Distance from `point` to the nearest line of the arrangement, skipping the lines in `skip`.
  [[nodiscard]] double distance_to_lines(const Eigen::Vector2d& point, std::span<const std::size_t> skip = {}) const;

 private:
  std::vector<LandmarkId> ids_;
  std::vector<Eigen::Vector2d> positions_;
  std::vector<LandmarkPair> pairs_;
  std::vector<LpbLine> lines_;
  std::vector<LineCrossing> crossings_;
};

/// 1 + C(n,2) + n(n−2) + 3·C(n,4): the region count of n landmarks in general position.
std::size_t general_position_region_count(std::size_t n);

/// An orientation region: a cell of the arrangement.
struct OrientationRegion {
  SignVector signs;                                    ///< over Arrangement::pairs(), no zeros
  Eigen::Vector2d interior = Eigen::Vector2d::Zero();  ///< a point inside it
};

/// Two regions across one LPB: they differ in that pair's sign only and share a piece of its line.
struct RegionAdjacency {
  std::size_t first = 0;  ///< region index, first < second
  std::size_t second = 0;
  std::size_t line = 0;  ///< the LPB between them
  friend bool operator==(const RegionAdjacency&, const RegionAdjacency&) = default;
  friend bool operator<(const RegionAdjacency& a, const RegionAdjacency& b) {
    return std::tie(a.first, a.second, a.line) < std::tie(b.first, b.second, b.line);
  }
};

class OrientationRegions {
 public:
  /// Enumerates the cells of `arrangement` (kept by reference: it must outlive this).
  explicit OrientationRegions(const Arrangement& arrangement);

  [[nodiscard]] std::span<const OrientationRegion> regions() const { return regions_; }
  /// Sorted; each pair of neighbours once, whatever the number of boundary pieces they share.
  [[nodiscard]] std::span<const RegionAdjacency> adjacency() const { return adjacency_; }
  /// Pieces of lines between consecutive crossings (rays included): the planar graph's edges.
  [[nodiscard]] std::size_t edge_count() const { return edge_count_; }
  /// Euler's formula on the planar graph of crossings and edges (one vertex at infinity):
  /// F = E − V + 1, or 2 for a single line.
  [[nodiscard]] std::size_t euler_region_count() const;

  /// The region containing `point`, or std::nullopt when it lies on an LPB line.
  [[nodiscard]] std::optional<std::size_t> region_of(const Eigen::Vector2d& point) const;
  /// The region with these signs, if the arrangement has it.
  [[nodiscard]] std::optional<std::size_t> region_with(const SignVector& signs) const;

 private:
  std::size_t add_region(const SignVector& signs, const Eigen::Vector2d& interior);

  const Arrangement* arrangement_;
  std::vector<OrientationRegion> regions_;
  std::map<SignVector, std::size_t> index_;
  std::vector<RegionAdjacency> adjacency_;
  std::size_t edge_count_ = 0;
};

}  // namespace neopipe::nav::qualnav
