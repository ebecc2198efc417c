#pragma once
// Plane-to-plane projective maps (the paper's matrix A: image (U, V, 1) -> workspace (X, Y, 1)):
// normalised DLT, RANSAC against outliers, and Levenberg-Marquardt refinement of the error in
// workspace units.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "calib/correspondence.hpp"

namespace neopipe::calib {

/// p' ~ H p in homogeneous coordinates, divided through.
Eigen::Vector2d apply(const Eigen::Matrix3d& h, const Eigen::Vector2d& p);

/// Normalised DLT (Hartley: each point set centred and scaled to mean distance sqrt 2) from pixels to
/// world, H(2,2) = 1. Throws CalibrationError for fewer than 4 points or degenerate (collinear or
/// coincident) points.
Eigen::Matrix3d fit_homography_dlt(const Correspondences& points);

struct RansacOptions {
  double inlier_mm = 1.0;     ///< a point is an inlier when its mapped error is below this
  int iterations = 2000;      ///< upper bound; stops early once the inlier ratio makes it pointless
  double confidence = 0.999;  ///< for the early stop
  std::uint64_t seed = 1;     ///< the same seed draws the same samples
};

struct HomographyFit {
  Eigen::Matrix3d image_to_world = Eigen::Matrix3d::Identity();
  std::vector<bool> inlier;  ///< per input point
  int inliers = 0;
};

/// RANSAC over minimal 4-point samples (non-degenerate ones only), then DLT on the best consensus
/// set, then refine_homography on it. Throws CalibrationError when no 4 points give a usable model.
HomographyFit fit_homography_ransac(const Correspondences& points, const RansacOptions& options = {});

/// Levenberg-Marquardt on the 8 free entries of H minimising the sum of squared distances, in the
/// world plane, between apply(H, pixel) and world. Starts from `initial` and never returns a map
/// with a larger sum than initial / initial(2,2); the result has H(2,2) = 1. Throws CalibrationError
/// when initial(2,2) is 0.
Eigen::Matrix3d refine_homography(const Eigen::Matrix3d& initial, const Correspondences& points);

}  // namespace neopipe::calib
