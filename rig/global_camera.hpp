#pragma once
// The rig's global camera and its calibration session: what the survey knows of the camera. Under
// the realism presets the camera is not the one its models describe (a lens beyond OpenCV's five
// terms, spheres whose centres are a radius above the table, a lamp that shades them): the session
// measures what the models miss.
//
//  1. Five views of a dot-grid board (15 x 15, pitch 5% of the workspace's shorter side; the first
//     flat on the table, the others raised and tipped for the lens), rendered under the realism,
//     give the full camera model of the board's face. The board is `board_thickness` thick: its face,
//     the calibrated plane, lies that far above the table.
//  2. One view of a check plate: marbles on a 12 x 12 grid of known places over the whole workspace.
//     Their weighted centroids (the engine's marble graph) against where the model projects their
//     centres (a radius above the table) give the centroid's lean (calib/centroid_bias.hpp): the
//     shading, highlight and shadow's bias, and what the lens model leaves, as a smooth field.
//  3. The same plate marbles, each corrected by a field fitted without it and mapped back to the
//     table through the model: their misses are the survey's error, told to the map-maker.
//
// A session depends only on the camera, the realism, the workspace, the marbles' size, the board and
// the seed, so it is cached (rig/calibration_cache.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "calib/calibration.hpp"
#include "calib/centroid_bias.hpp"
#include "sim/camera.hpp"
#include "sim/cameras.hpp"
#include "sim/realism.hpp"
#include "sim/rendering.hpp"

namespace neopipe::rig {

struct GlobalCameraSettings {
  sim::Realism realism = sim::Realism::rig;
  sim::GlobalCameraConfig camera;  ///< pose and image size (its lens comes from the realism)
  /// mm: the calibration board's printed face lies this far above the table when the board lies
  /// flat on it. Today's ideal board is a print on the table itself.
  std::optional<double> board_thickness;  ///< none: 3 mm, or 0 under ideal
  int bias_degree = 2;                    ///< of the centroid's lean, a polynomial in the pixel position
  std::uint64_t seed = 1;                 ///< the camera's noise (its own stream of this seed)

  [[nodiscard]] double thickness() const;
};

/// The camera and its rendering, as the rig has them (the truth: the survey never reads these).
struct GlobalCameraRig {
  sim::Rendering rendering;
  sim::PinholeCamera camera;
};
GlobalCameraRig make_global_camera_rig(const Eigen::Vector2d& workspace, const GlobalCameraSettings& settings);

/// What the session measured: all the survey may use.
struct GlobalCameraSession {
  calib::Calibration calibration;      ///< of the board's face, in workspace millimetres
  double plane_height = 0;             ///< mm: the calibrated plane above the table (the board's thickness)
  double marble_height = 0;            ///< mm: the marbles' centres above the table (their outlines' centre)
  calib::CentroidBias bias;            ///< the marble graph's weighted centroid minus the centre's projection
  calib::ErrorStats bias_held_out_px;  ///< the field's k-fold miss on the plate, px
  /// The plate marbles through the whole survey (centroid, held-out field, model, height), mm
  /// against their known places: the survey's error.
  calib::ErrorStats plate_held_out_mm;
  int plate_marbles = 0;

  /// The position error the map-maker is told, sd per axis (mm): the plate's held-out RMS over the
  /// two axes (a mean miss counts: it is error all the same).
  [[nodiscard]] double told_sigma() const;
  /// Workspace positions (mm) of marbles whose weighted centroids are `centroids` (px).
  [[nodiscard]] std::vector<Eigen::Vector2d> locate(const std::vector<Eigen::Vector2d>& centroids) const;
};

/// Runs the session (about two seconds). Throws SurveyError when a view's target is not found or
/// the plate does not show every marble.
GlobalCameraSession calibrate_session(const Eigen::Vector2d& workspace, double marble_diameter,
                                      const GlobalCameraSettings& settings);

/// Everything a session depends on, spelled out: its cache key.
std::string session_key(const Eigen::Vector2d& workspace, double marble_diameter, const GlobalCameraSettings& settings);

/// The check plate's marbles (workspace mm): a 12 x 12 grid over all but the outer 2% of the
/// workspace, in raster order.
std::vector<Eigen::Vector2d> check_plate(const Eigen::Vector2d& workspace);

/// The noise frames of a session: the board's views 0..4, the check plate's, the survey's world's.
inline constexpr std::int64_t kCheckPlateFrame = 5;
inline constexpr std::int64_t kWorldFrame = 6;

/// The engine's weighted centroids of the marbles in a global camera frame, in raster order.
std::vector<Eigen::Vector2d> marble_centroids(const cv::Mat& frame);

}  // namespace neopipe::rig
