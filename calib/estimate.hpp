#pragma once
// Estimating a calibration from correspondences, with the error report: fit, held-out (k-fold)
// and reprojection errors, and both models' held-out errors where both can be fitted.

#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "calib/calibration.hpp"
#include "calib/correspondence.hpp"
#include "calib/homography.hpp"

namespace neopipe::calib {

/// One image of the target: its points' pixels and their positions in the target's own plane (mm).
struct View {
  std::string name;
  Correspondences points;
};

struct EstimateOptions {
  RansacOptions ransac{2.0};  ///< inlier_mm: generous, since the homography does not model the lens
  int folds = 5;              ///< for the held-out error
};

/// The plane homography from `workspace` (pixels and workspace positions, mm). Throws
/// CalibrationError for too few or degenerate points.
Calibration calibrate_homography(const Correspondences& workspace, cv::Size image_size,
                                 const EstimateOptions& options = {});

/// The full model: intrinsics and distortion from every view (cv::calibrateCamera), then the
/// homography from undistorted pixels to the workspace, fitted on `workspace` (the view of the
/// target lying on the workspace, its points in workspace mm). `views` holds every view in target
/// coordinates, the workspace view first. Needs at least 3 views.
Calibration calibrate_full(const std::vector<View>& views, const Correspondences& workspace, cv::Size image_size,
                           const EstimateOptions& options = {});

}  // namespace neopipe::calib
