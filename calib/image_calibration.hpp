#pragma once
// Calibration from images of a target, as `neopipe calibrate IMAGES --target ...` does it: find the
// target in every view, place the first view's points on the workspace, fit the homography or the
// full model. Here (not in apps/) so that the command line and the Python module run the same steps.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "calib/calibration.hpp"
#include "calib/correspondence.hpp"

namespace neopipe::calib {

struct TargetSpec {
  bool dots = false;  ///< bright dots (else a chessboard's inner corners)
  int cols = 0;
  int rows = 0;
  double pitch = 0;  ///< mm
};

/// "dots:COLSxROWS:PITCHmm" or "chessboard:COLSxROWS:SQUAREmm". Throws std::invalid_argument
/// ("--target TEXT: expected ...", the command line's words) when malformed.
TargetSpec parse_target(const std::string& text);

struct ImageCalibrationOptions {
  TargetSpec target;
  /// Where the first image's first point lies on the workspace (X, Y mm) and its rows' direction
  /// from East (degrees).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::string model = "auto";  ///< homography, full, or auto (full from 3 views found)
  double inlier_mm = 2.0;      ///< RANSAC: a point further than this from the fit is an outlier
  std::function<void(std::size_t images_done)> progress;
};

struct ImageCalibration {
  Calibration calibration;
  Correspondences workspace;  ///< the first view's points: pixel and workspace position
};

/// Reads the images (gray), finds the target in each, and fits. The first image must show the
/// target (lying on the workspace); views where it is not found are rejected and reported. Throws
/// CalibrationError naming the image for a missing or unreadable file, a view of another size, or a
/// first view without the target.
ImageCalibration calibrate_images(const std::vector<std::string>& images, const ImageCalibrationOptions& options);

}  // namespace neopipe::calib
