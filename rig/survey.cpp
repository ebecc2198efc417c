#include "rig/survey.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "calib/dot_grid_detector.hpp"
#include "calib/estimate.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/kernel_registry.hpp"
#include "rig/seeds.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/random.hpp"
#include "sim/target_renderer.hpp"

namespace neopipe::rig {
namespace {

using Eigen::Vector2d;

void measure_errors(const sim::World& world, Survey& s) {
  double sum = 0;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const double e = (s.workspace.objects[i] - world.objects[i]).norm();
    sum += e * e;
    s.max_error = std::max(s.max_error, e);
  }
  s.rms_error = world.objects.empty() ? 0 : std::sqrt(sum / static_cast<double>(world.objects.size()));
}

// The calibration session: a 15 x 15 dot grid (pitch 5% of the workspace's shorter side, 25 mm on
// the default 500 mm world) centred on the workspace for the first view, then raised and tipped for
// the lens. The same recipe as the calibration's own end-to-end test, scaled to the workspace.
calib::Calibration calibrate_global_camera(const sim::PinholeCamera& camera, const sim::MarbleRenderer& renderer,
                                           const Vector2d& workspace) {
  const double scale = std::min(workspace.x(), workspace.y()) / 500;
  const sim::CalibrationTarget grid{sim::TargetKind::dots, 15, 15, 25 * scale, 9 * scale};
  const Vector2d origin = (workspace - Vector2d(14, 14) * grid.pitch) / 2;
  const auto pose = [&](double dx, double dy, double z, double theta, double tilt_x, double tilt_y) {
    return sim::target_pose(origin.x() + dx * scale, origin.y() + dy * scale, z * scale, theta, tilt_x, tilt_y);
  };
  const std::vector<sim::TargetPose> poses{pose(0, 0, 0, 0, 0, 0), pose(5, -5, 40, 3, 20, 0),
                                           pose(-5, 5, 30, -3, 0, 22), pose(5, 5, 50, 2, -15, 12),
                                           pose(0, -5, 20, -2, 12, -15)};
  const std::vector<Vector2d> plane = sim::target_points(grid);
  std::vector<calib::View> views;
  for (std::size_t v = 0; v < poses.size(); ++v) {
    const cv::Mat image = sim::render_target(grid, poses[v], camera, renderer, static_cast<std::int64_t>(v));
    const auto found = calib::find_dot_grid(image, grid.cols, grid.rows);
    if (!found) throw SurveyError(fmt::format("global camera survey: calibration view {}: dot grid not found", v));
    calib::View view{fmt::format("view {}", v), {}};
    for (std::size_t i = 0; i < plane.size(); ++i) view.points.push_back({(*found)[i], plane[i]});
    views.push_back(std::move(view));
  }
  calib::Correspondences on_workspace = views.front().points;
  for (auto& p : on_workspace) p.world += origin;
  return calib::calibrate_full(views, on_workspace, camera.size());
}

// Each world object takes the one surveyed position nearest to it; a blob claimed twice, or an
// object without a blob within its radius, means marbles merged or vanished in the image.
std::vector<Vector2d> assign_world_ids(const sim::World& world, const std::vector<Vector2d>& surveyed) {
  if (surveyed.size() != world.objects.size()) {
    throw SurveyError(fmt::format(
        "global camera survey: the image shows {} marbles of the world's {} (marbles touching in its pixels); "
        "survey with --sigma-map instead",
        surveyed.size(), world.objects.size()));
  }
  std::vector<Vector2d> out(world.objects.size());
  std::vector<int> claimed(surveyed.size(), -1);
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t at = 0;
    for (std::size_t j = 0; j < surveyed.size(); ++j) {
      const double d = (surveyed[j] - world.objects[i]).squaredNorm();
      if (d < best) {
        best = d;
        at = j;
      }
    }
    if (std::sqrt(best) > world.marble_diameter / 2 || claimed[at] >= 0) {
      throw SurveyError(fmt::format("global camera survey: object {} was not found in the global camera's image", i));
    }
    claimed[at] = static_cast<int>(i);
    out[i] = surveyed[at];
  }
  return out;
}

}  // namespace

Survey gaussian_survey(const sim::World& world, double sigma, std::uint64_t seed) {
  Survey s;
  s.method = "gaussian";
  s.sigma = sigma;
  s.workspace = {world.size, {}};
  s.workspace.objects.reserve(world.objects.size());
  sim::Random random(stream_seed(seed, streams::gaussian_survey));
  for (const Vector2d& p : world.objects) {
    const double x = random.normal(p.x(), sigma);
    const double y = random.normal(p.y(), sigma);
    s.workspace.objects.emplace_back(std::clamp(x, 0.0, world.size.x()), std::clamp(y, 0.0, world.size.y()));
  }
  measure_errors(world, s);
  return s;
}

Survey global_camera_survey(const sim::World& world, std::uint64_t seed) {
  const sim::PinholeCamera camera = sim::make_global_camera(world.size);
  sim::ImageModel model;
  model.seed = stream_seed(seed, streams::global_camera);
  const sim::MarbleRenderer renderer(model, camera.size());
  const calib::Calibration calibration = calibrate_global_camera(camera, renderer, world.size);

  // Frame index 5: the calibration views used 0..4, and every frame has its own noise.
  const cv::Mat image = renderer.render(world.objects, world.marble_diameter, camera, 5);
  const auto results =
      pipeline::run_frames(pipeline::compile(pipeline::marble_graph(), pipeline::standard_kernels()), {image});
  const auto& blobs = std::get<pipeline::BlobList>(results.at(0).outputs.at(0));
  std::vector<Vector2d> pixels;
  pixels.reserve(blobs.size());
  for (const auto& b : blobs) pixels.emplace_back(b.wcx, b.wcy);

  Survey s;
  s.method = "global_camera";
  s.sigma = calibration.report.held_out.sd.maxCoeff();
  s.workspace = {world.size, assign_world_ids(world, calibration.to_world(pixels))};
  for (Vector2d& p : s.workspace.objects) p = p.cwiseMax(Vector2d::Zero()).cwiseMin(world.size);
  measure_errors(world, s);
  return s;
}

}  // namespace neopipe::rig
