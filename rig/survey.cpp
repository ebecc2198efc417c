#include "rig/survey.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rig/calibration_cache.hpp"
#include "rig/seeds.hpp"
#include "sim/random.hpp"
#include "sim/scene_renderer.hpp"

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

GlobalCameraSession global_camera_session(const sim::World& world, const SurveySettings& settings) {
  const auto calibrate = [&] { return calibrate_session(world.size, world.marble_diameter, settings.camera); };
  if (!settings.cache_dir) return calibrate();
  const CalibrationCache cache(*settings.cache_dir, settings.note);
  return cache.get(session_key(world.size, world.marble_diameter, settings.camera), calibrate);
}

Survey global_camera_survey(const sim::World& world, const SurveySettings& settings) {
  const GlobalCameraSession session = global_camera_session(world, settings);
  const GlobalCameraRig rig = make_global_camera_rig(world.size, settings.camera);
  const sim::SceneRenderer renderer(rig.rendering, rig.camera);
  const cv::Mat image = renderer.render(world.objects, world.marble_diameter, rig.camera, kWorldFrame);

  Survey s;
  s.method = "global_camera";
  s.realism = sim::realism_name(settings.camera.realism);
  s.sigma = session.told_sigma();
  s.session = session;
  s.workspace = {world.size, assign_world_ids(world, session.locate(marble_centroids(image)))};
  for (Vector2d& p : s.workspace.objects) p = p.cwiseMax(Vector2d::Zero()).cwiseMin(world.size);
  measure_errors(world, s);
  return s;
}

}  // namespace neopipe::rig
