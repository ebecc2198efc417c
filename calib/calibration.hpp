#pragma once
// A calibration of the global camera: how a pixel maps to the workspace plane, and how well.
// Two models: a plane homography on raw pixels (the paper's matrix A), or the full camera model
// (intrinsics and lens distortion from several views, then a homography on undistorted pixels).
// Saved as OpenCV FileStorage YAML so OpenCV users can read it.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "calib/correspondence.hpp"

namespace neopipe::calib {

enum class Model { homography, full };

std::string model_name(Model m);

/// Errors of mapped points against their known workspace positions, mm.
struct ErrorStats {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();  ///< per axis (X, Y)
  Eigen::Vector2d sd = Eigen::Vector2d::Zero();    ///< per axis, sample standard deviation
  double rms = 0;                                  ///< of the error's length
  double max = 0;
  int points = 0;
};

/// Mapped minus true, per point.
ErrorStats error_stats(const std::vector<Eigen::Vector2d>& errors);

struct CalibrationReport {
  ErrorStats fit;                       ///< on the workspace points the mapping was fitted to
  ErrorStats held_out;                  ///< each point predicted by a mapping fitted without it (k-fold)
  double reprojection_rms_px = 0;       ///< workspace points mapped back into the image, vs where they were seen
  double homography_held_out_rms = -1;  ///< the plane homography's held-out RMS on the same points (-1: not run)
  double full_held_out_rms = -1;        ///< the full model's (-1: not run: too few views)
  int views_used = 0;
  int views_rejected = 0;  ///< images where the target was not found
  int points_used = 0;
  int points_rejected = 0;            ///< outliers RANSAC set aside
  std::vector<std::string> rejected;  ///< "image: why", one per rejected view
};

struct Calibration {
  Model model = Model::homography;
  cv::Size image_size;                                           ///< 0 x 0 when unknown (point pairs)
  cv::Mat camera_matrix;                                         ///< 3x3 CV_64F (full model; empty for the homography)
  cv::Mat distortion_coefficients;                               ///< 1x5 CV_64F (full model; empty for the homography)
  Eigen::Matrix3d image_to_world = Eigen::Matrix3d::Identity();  ///< on undistorted pixels for the full model
  CalibrationReport report;

  /// Workspace positions (mm) of pixels.
  [[nodiscard]] std::vector<Eigen::Vector2d> to_world(const std::vector<Eigen::Vector2d>& pixels) const;
  /// Where workspace points appear in the image (px).
  [[nodiscard]] std::vector<Eigen::Vector2d> to_pixel(const std::vector<Eigen::Vector2d>& world) const;
};

/// Writes `camera_matrix`, `distortion_coefficients` (full model), `image_to_world`, `image_size`,
/// `model`, `reprojection_rms_px` and the report's figures. Throws CalibrationError naming the path.
void save_calibration(const Calibration& c, const std::string& path);

/// Reads a file written by save_calibration (or by hand with the same keys). Throws CalibrationError
/// naming the file and the missing or malformed key.
Calibration load_calibration(const std::string& path);

}  // namespace neopipe::calib
