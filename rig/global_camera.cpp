#include "rig/global_camera.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "calib/dot_grid_detector.hpp"
#include "calib/estimate.hpp"
#include "calib/plane_pose.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/kernel_registry.hpp"
#include "rig/seeds.hpp"
#include "rig/survey.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/target_renderer.hpp"

namespace neopipe::rig {
namespace {

using Eigen::Vector2d;

// Bumped whenever the session's recipe changes, so cached sessions of the old recipe go stale.
constexpr int kRecipe = 3;

// The board's views: a 15 x 15 dot grid (pitch 5% of the workspace's shorter side, 25 mm on the
// default 500 mm world) centred on the workspace, flat on the table first, then raised and tipped
// for the lens; the same recipe as the calibration's own end-to-end test, scaled to the workspace.
struct BoardSession {
  sim::CalibrationTarget grid;
  Vector2d origin;  ///< workspace position of the grid's first dot in the flat view
  std::vector<sim::TargetPose> poses;
};

BoardSession board_session(const Vector2d& workspace, double thickness) {
  const double scale = std::min(workspace.x(), workspace.y()) / 500;
  BoardSession b;
  b.grid = {sim::TargetKind::dots, 15, 15, 25 * scale, 9 * scale};
  b.origin = (workspace - Vector2d(14, 14) * b.grid.pitch) / 2;
  const auto pose = [&](double dx, double dy, double z, double theta, double tilt_x, double tilt_y) {
    return sim::target_pose(b.origin.x() + dx * scale, b.origin.y() + dy * scale, thickness + z * scale, theta, tilt_x,
                            tilt_y);
  };
  b.poses = {pose(0, 0, 0, 0, 0, 0), pose(5, -5, 40, 3, 20, 0), pose(-5, 5, 30, -3, 0, 22), pose(5, 5, 50, 2, -15, 12),
             pose(0, -5, 20, -2, 12, -15)};
  return b;
}

}  // namespace

std::vector<Vector2d> check_plate(const Vector2d& workspace) {
  std::vector<Vector2d> out;
  constexpr int n = 12;
  // Out to the workspace's edges: the lean is fitted as a polynomial, which must not extrapolate to
  // marbles in the image's corners, where defocus and the lens's misfit are largest.
  const Vector2d first = 0.02 * workspace;
  const Vector2d step = 0.96 * workspace / (n - 1);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) out.emplace_back(first.x() + i * step.x(), first.y() + j * step.y());
  }
  return out;
}

double GlobalCameraSettings::thickness() const {
  if (board_thickness) return *board_thickness;
  return realism == sim::Realism::ideal ? 0.0 : 3.0;
}

GlobalCameraRig make_global_camera_rig(const Vector2d& workspace, const GlobalCameraSettings& s) {
  sim::Rendering rendering = sim::rendering_for(s.realism, sim::CameraKind::global, workspace);
  rendering.sensor.seed = stream_seed(s.seed, streams::global_camera);
  sim::PinholeCamera camera = sim::make_global_camera(workspace, s.camera, rendering);
  return {rendering, camera};
}

std::vector<Vector2d> marble_centroids(const cv::Mat& frame) {
  pipeline::InlineRunner runner(pipeline::compile(pipeline::marble_graph(), pipeline::standard_kernels()));
  const auto& blobs = std::get<pipeline::BlobList>(runner.run(frame).at(0));
  std::vector<Vector2d> out;
  out.reserve(blobs.size());
  for (const auto& b : blobs) out.emplace_back(b.wcx, b.wcy);
  return out;
}

double GlobalCameraSession::told_sigma() const {
  return plate_held_out_mm.rms / std::sqrt(2.0);
}

std::vector<Vector2d> GlobalCameraSession::locate(const std::vector<Vector2d>& centroids) const {
  std::vector<Vector2d> centres;
  centres.reserve(centroids.size());
  for (const Vector2d& c : centroids) centres.push_back(bias.correct(c));
  return calib::to_world_at_height(calibration, centres, marble_height - plane_height);
}

GlobalCameraSession calibrate_session(const Vector2d& workspace, double marble_diameter,
                                      const GlobalCameraSettings& settings) {
  const GlobalCameraRig rig = make_global_camera_rig(workspace, settings);
  const sim::SceneRenderer renderer(rig.rendering, rig.camera);
  GlobalCameraSession session;
  session.plane_height = settings.thickness();
  session.marble_height = rig.rendering.shape == sim::MarbleShape::sphere ? marble_diameter / 2 : 0.0;

  // 1. The board.
  const BoardSession board = board_session(workspace, session.plane_height);
  const std::vector<Vector2d> plane = sim::target_points(board.grid);
  std::vector<calib::View> views;
  for (std::size_t v = 0; v < board.poses.size(); ++v) {
    const cv::Mat image =
        sim::render_target(board.grid, board.poses[v], rig.camera, renderer, static_cast<std::int64_t>(v));
    const auto found = calib::find_dot_grid(image, board.grid.cols, board.grid.rows);
    if (!found) throw SurveyError(fmt::format("global camera calibration: board view {}: dot grid not found", v));
    calib::View view{fmt::format("view {}", v), {}};
    for (std::size_t i = 0; i < plane.size(); ++i) view.points.push_back({(*found)[i], plane[i]});
    views.push_back(std::move(view));
  }
  calib::Correspondences on_face = views.front().points;
  for (auto& p : on_face) p.world += board.origin;
  session.calibration = calib::calibrate_full(views, on_face, rig.camera.size());

  // 2. The plate: each marble takes the centroid nearest where the model projects it.
  const std::vector<Vector2d> plate = check_plate(workspace);
  const cv::Mat image = renderer.render(plate, marble_diameter, rig.camera, kCheckPlateFrame);
  const std::vector<Vector2d> centroids = marble_centroids(image);
  const double height = session.marble_height - session.plane_height;
  const std::vector<Vector2d> projected = calib::to_pixel_at_height(session.calibration, plate, height);
  // A centroid belongs to the plate marble it lies within a radius of (the lean is a fraction of it).
  const Vector2d middle = 0.5 * workspace;
  const auto scale = calib::to_pixel_at_height(session.calibration, {middle, middle + Vector2d(1, 0)}, height);
  const double radius_px = 0.5 * marble_diameter * (scale[1] - scale[0]).norm();
  std::vector<Vector2d> matched;
  for (std::size_t i = 0; i < plate.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    Vector2d at = Vector2d::Zero();
    for (const Vector2d& c : centroids) {
      const double d = (c - projected[i]).norm();
      if (d < best) {
        best = d;
        at = c;
      }
    }
    if (!(best < radius_px)) {
      throw SurveyError(fmt::format("global camera calibration: check plate marble {} not found in its image", i));
    }
    matched.push_back(at);
  }
  const calib::CentroidBiasFit fit =
      calib::fit_centroid_bias(matched, projected, rig.camera.size(), settings.bias_degree, 10);
  session.bias = fit.bias;
  session.bias_held_out_px = fit.held_out;

  // 3. The plate through the whole survey, each marble by a field fitted without it.
  const std::vector<Vector2d> located = calib::to_world_at_height(session.calibration, fit.held_out_corrected, height);
  std::vector<Vector2d> misses;
  for (std::size_t i = 0; i < plate.size(); ++i) misses.emplace_back(located[i] - plate[i]);
  session.plate_held_out_mm = calib::error_stats(misses);
  session.plate_marbles = static_cast<int>(plate.size());
  return session;
}

std::string session_key(const Vector2d& workspace, double marble_diameter, const GlobalCameraSettings& s) {
  const GlobalCameraRig rig = make_global_camera_rig(workspace, s);
  const sim::Rendering& r = rig.rendering;
  const auto& k = rig.camera.intrinsics();
  std::string key = fmt::format("neopipe global camera session, recipe {}\n", kRecipe);
  key += fmt::format("workspace {:.17g} {:.17g}; marble {:.17g}; board {:.17g}; bias degree {}\n", workspace.x(),
                     workspace.y(), marble_diameter, s.thickness(), s.bias_degree);
  key += fmt::format("realism {}; seed {}\n", sim::realism_name(s.realism), s.seed);
  key += fmt::format("intrinsics {:.17g} {:.17g} {:.17g} {:.17g} {}x{}\n", k.fx, k.fy, k.cx, k.cy, k.size.width,
                     k.size.height);
  key += fmt::format("rotation {:.17g}\ntranslation {:.17g}\n", fmt::join(rig.camera.rotation().reshaped(), " "),
                     fmt::join(rig.camera.translation(), " "));
  key +=
      fmt::format("lens {:.17g} | {:.17g}\n", fmt::join(r.lens.opencv, " "), fmt::join(r.lens.extra.as_array(), " "));
  key += fmt::format("shape {}; surfaces {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {}\n", static_cast<int>(r.shape),
                     r.surfaces.table, r.surfaces.marble, r.surfaces.disk_rim, r.surfaces.texture,
                     r.surfaces.texture_scale, r.surfaces.texture_seed);
  if (r.light) {
    key += fmt::format("light {:.17g}; {:.17g} {:.17g} {:.17g} {}\n", fmt::join(r.light->position, " "),
                       r.light->ambient, r.light->specular, r.light->shininess, r.light->shadows);
  }
  key += fmt::format(
      "defocus {:.17g} {:.17g}; sensor {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {}; interlace {}\n",
      r.defocus.centre, r.defocus.corner, r.sensor.read_noise, r.sensor.full_well.value_or(-1), r.sensor.prnu,
      r.sensor.vignetting, r.sensor.gradient, r.sensor.gradient_angle_deg, r.sensor.seed, r.interlace);
  return key;
}

}  // namespace neopipe::rig
