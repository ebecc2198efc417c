#pragma once
// Where a viewframe was taken, in a frame of landmark positions (qualnav.md §3; seed 003 §2).
//
// Constant-angle locus: in the frame L1 = (0,0), L2 = (s,0), observers that see the pair under θ
// lie on the circle of radius (s/2)·cscθ centred (s/2, (s/2)·cotθ). Loc_ij is the set of points
// whose signed angle L_i P L_j lies within e_ij = e_i + e_j of the observed one and whose distances
// to L_i and L_j lie in the viewframe's range intervals; the localization is the intersection over
// the pairs whose landmarks have positions in the frame. Decision: rasterised on a 1 mm grid
// (cell centres at multiples of the resolution), centroid = mean cell.
//
// The raster is searched coarse to fine: a 16-cell block is opened only when the constraints,
// widened by how much they can change within the block, may hold somewhere in it, so a thin arc
// hundreds of mm long costs thousands of cell tests, not millions.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

struct Circle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0;
};

/// The constant-angle locus of the pair L1 = (0,0), L2 = (s,0) seen under θ ∈ (0, π): the circle of
/// radius (s/2)·cscθ centred (s/2, (s/2)·cotθ) (its arc above the x axis for counter-clockwise θ).
Circle constant_angle_locus(double s, double theta);
/// The range r1 = |P − L1| of the observer on that locus whose angle at L1 is φ:
/// r1 = s·cosφ + s·cotθ·sinφ.
double locus_range(double s, double theta, double phi);
/// The angle φ at L1 of the observer seeing the pair under θ at ranges r1, r2:
/// cotφ = (r1/r2)·cscθ − cotθ, φ ∈ (0, π).
double locus_angle(double r1, double r2, double theta);

/// Landmark positions in a frame (mm), by id.
using FramePositions = std::map<LandmarkId, Eigen::Vector2d>;

struct LocalizationOptions {
  double resolution_mm = 1;         ///< the raster (Decision: 1 mm)
  double error_scale = 1;           ///< multiplies every e_ij (a fallback may widen them)
  bool use_ranges = true;           ///< intersect with the range annuli
  bool keep_cells = false;          ///< fill Localization::cells
  std::size_t max_cells = 4000000;  ///< a raster larger than this many cells is refused (empty)
};

struct Localization {
  std::size_t count = 0;  ///< cells in the region
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  Eigen::Vector2d min = Eigen::Vector2d::Zero();  ///< the cells' bounding box
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> cells;  ///< with keep_cells
  int pairs = 0;                       ///< pairs intersected
  [[nodiscard]] bool empty() const { return count == 0; }
  [[nodiscard]] double area_mm2(double resolution_mm = 1) const {
    return static_cast<double>(count) * resolution_mm * resolution_mm;
  }
};

/// The localization of `view` in the frame `positions` (landmarks of the viewframe without a
/// position are ignored). Empty when fewer than two landmarks have positions or nothing satisfies
/// every constraint.
Localization localize(const Viewframe& view, const FramePositions& positions, const LocalizationOptions& options = {});

}  // namespace neopipe::nav::qualnav
