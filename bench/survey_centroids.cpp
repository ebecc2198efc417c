// neopipe_survey_centroids: which centroid the global camera's survey should use. For each marble of
// the default worlds under a realism preset, three estimates of where its centre projects: the
// binary centroid (mean pixel position), the intensity-weighted centroid (the engine's marble graph:
// weights = gray - 60) and a fit of a shaded-sphere model (calib/marble_fit.hpp); each raw, and each
// corrected by the lean that the session's check plate measures for that estimate
// (calib/centroid_bias.hpp). Errors against the truth: px for where the centre projects, mm for the
// surveyed position (each corrected centroid mapped to the table at the marbles' height through the
// session's calibration). docs/calibration.md has the table and the choice.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calib/centroid_bias.hpp"
#include "calib/marble_fit.hpp"
#include "calib/plane_pose.hpp"
#include "calib/residual_plot.hpp"
#include "kernels/blobs.hpp"
#include "rig/global_camera.hpp"
#include "sim/marble_truth.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace {

using Eigen::Vector2d;
namespace rig = neopipe::rig;
namespace sim = neopipe::sim;
namespace calib = neopipe::calib;

enum Estimate { binary, weighted, fitted, kEstimates };
constexpr std::array<const char*, kEstimates> kNames{"binary", "weighted", "fitted"};

// The three estimates for every marble whose blob lies nearest `expected` (px), in that order.
struct Estimates {
  std::array<std::vector<Vector2d>, kEstimates> at;
  double fit_seconds = 0;
};

Estimates estimate(const cv::Mat& image, const std::vector<Vector2d>& expected, double radius_px, bool fit) {
  cv::Mat excess;
  cv::subtract(image, cv::Scalar(60), excess);
  const auto blobs = neopipe::kernels::extract_blobs(excess, {0, neopipe::kernels::Connectivity::eight}, excess);
  Estimates e;
  for (const Vector2d& x : expected) {
    const neopipe::kernels::Blob* best = nullptr;
    double d = std::numeric_limits<double>::infinity();
    for (const auto& b : blobs) {
      const double dist = (Vector2d(b.wcx, b.wcy) - x).norm();
      if (dist < d) {
        d = dist;
        best = &b;
      }
    }
    if (best == nullptr) throw std::runtime_error("no blob at all");
    e.at[binary].emplace_back(best->cx, best->cy);
    e.at[weighted].emplace_back(best->wcx, best->wcy);
    if (fit) {
      const auto t0 = std::chrono::steady_clock::now();
      const auto f = calib::fit_marble(image, {best->cx, best->cy}, radius_px);
      e.fit_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      e.at[fitted].push_back(f ? f->centre : Vector2d(best->cx, best->cy));
    }
  }
  return e;
}

struct Tally {
  Vector2d raw_sum = Vector2d::Zero();
  double raw2 = 0;
  double corrected2 = 0;
  double raw_mm2 = 0;
  double corrected_mm2 = 0;
  int n = 0;
};

}  // namespace

namespace {

int run(int argc, char** argv) {
  CLI::App app{"Centroid bias of the global camera's survey: binary, weighted and fitted, raw and corrected"};
  std::string realism = "rig";
  int worlds = 3;
  bool fit = false;
  std::string plot;
  app.add_option("--realism", realism, "Preset")
      ->check(CLI::IsMember({"ideal", "rig", "harsh"}))
      ->capture_default_str();
  app.add_option("--worlds", worlds, "Default worlds (100 marbles, seeds 1..N)")->capture_default_str();
  app.add_flag("--fit", fit, "Also the shaded-sphere model fit (about 0.2 s per marble)");
  app.add_option("--plot", plot,
                 "Write PREFIX-raw.png and PREFIX-corrected.png: the first world's surveyed minus true positions "
                 "by the weighted centroid, before and after the lean's correction")
      ->type_name("PREFIX");
  CLI11_PARSE(app, argc, argv);

  std::array<Tally, kEstimates> tally{};
  double fit_seconds = 0;
  for (int w = 1; w <= worlds; ++w) {
    sim::WorldRequest request;
    request.seed = static_cast<std::uint64_t>(w);
    const sim::World world = sim::generate_world(request);
    rig::GlobalCameraSettings settings;
    settings.realism = sim::parse_realism(realism);
    settings.seed = static_cast<std::uint64_t>(w);
    const rig::GlobalCameraSession session = rig::calibrate_session(world.size, world.marble_diameter, settings);
    const rig::GlobalCameraRig r = rig::make_global_camera_rig(world.size, settings);
    const sim::SceneRenderer renderer(r.rendering, r.camera);
    const double height = session.marble_height - session.plane_height;
    const Vector2d middle = 0.5 * world.size;
    const auto scale = calib::to_pixel_at_height(session.calibration, {middle, middle + Vector2d(1, 0)}, height);
    const double radius_px = 0.5 * world.marble_diameter * (scale[1] - scale[0]).norm();

    // Each estimate's own lean, from the check plate as the session measures the weighted one's.
    const std::vector<Vector2d> plate = rig::check_plate(world.size);
    const std::vector<Vector2d> plate_projected = calib::to_pixel_at_height(session.calibration, plate, height);
    const Estimates on_plate = estimate(renderer.render(plate, world.marble_diameter, r.camera, rig::kCheckPlateFrame),
                                        plate_projected, radius_px, fit);
    const auto truth = sim::marble_truth(world.objects, world.marble_diameter, r.camera, r.rendering.shape);
    std::vector<Vector2d> centres;
    centres.reserve(truth.size());
    for (const auto& t : truth) centres.emplace_back(t.u, t.v);
    const Estimates on_world = estimate(
        renderer.render(world.objects, world.marble_diameter, r.camera, rig::kWorldFrame), centres, radius_px, fit);
    fit_seconds += on_world.fit_seconds + on_plate.fit_seconds;
    for (int k = 0; k < kEstimates; ++k) {
      if (on_world.at[static_cast<std::size_t>(k)].empty()) continue;
      const calib::CentroidBias lean =
          calib::fit_centroid_bias(on_plate.at[static_cast<std::size_t>(k)], plate_projected, r.camera.size(), 2).bias;
      const auto& found = on_world.at[static_cast<std::size_t>(k)];
      std::vector<Vector2d> corrected;
      for (const Vector2d& p : found) corrected.push_back(lean.correct(p));
      const auto raw_mm = calib::to_world_at_height(session.calibration, found, height);
      const auto corrected_mm = calib::to_world_at_height(session.calibration, corrected, height);
      if (k == weighted && w == 1 && !plot.empty()) {
        calib::Correspondences at;
        std::vector<Vector2d> raw_errors;
        std::vector<Vector2d> corrected_errors;
        for (std::size_t i = 0; i < found.size(); ++i) {
          const Vector2d w_true = world.objects[static_cast<std::size_t>(truth[i].id)];
          at.push_back({found[i], w_true});
          raw_errors.emplace_back(raw_mm[i] - w_true);
          corrected_errors.emplace_back(corrected_mm[i] - w_true);
        }
        calib::write_residual_plot(at, raw_errors, realism + ": weighted centroids, surveyed minus true (mm)",
                                   plot + "-raw.png");
        calib::write_residual_plot(at, corrected_errors,
                                   realism + ": the same, corrected for the lean the check plate measured",
                                   plot + "-corrected.png");
      }
      Tally& t = tally[static_cast<std::size_t>(k)];
      for (std::size_t i = 0; i < found.size(); ++i) {
        const Vector2d w_true = world.objects[static_cast<std::size_t>(truth[i].id)];
        t.raw_sum += found[i] - centres[i];
        t.raw2 += (found[i] - centres[i]).squaredNorm();
        t.corrected2 += (corrected[i] - centres[i]).squaredNorm();
        t.raw_mm2 += (raw_mm[i] - w_true).squaredNorm();
        t.corrected_mm2 += (corrected_mm[i] - w_true).squaredNorm();
        ++t.n;
      }
    }
  }
  std::cout << fmt::format("{} realism, {} default worlds of 100 marbles: error of each estimate against the truth\n",
                           realism, worlds)
            << fmt::format("{:<10} {:>20} {:>12} {:>16} {:>12} {:>16}\n", "estimate", "mean lean px (u, v)",
                           "raw RMS px", "corrected RMS px", "raw RMS mm", "corrected RMS mm");
  for (int k = 0; k < kEstimates; ++k) {
    const Tally& t = tally[static_cast<std::size_t>(k)];
    if (t.n == 0) continue;
    const double n = t.n;
    std::cout << fmt::format("{:<10} {:>9.3f}, {:>8.3f} {:>12.3f} {:>16.3f} {:>12.4f} {:>16.4f}\n",
                             kNames[static_cast<std::size_t>(k)], t.raw_sum.x() / n, t.raw_sum.y() / n,
                             std::sqrt(t.raw2 / n), std::sqrt(t.corrected2 / n), std::sqrt(t.raw_mm2 / n),
                             std::sqrt(t.corrected_mm2 / n));
  }
  if (fit) {
    std::cout << fmt::format("model fit: {:.3f} s per marble\n", fit_seconds / (tally[fitted].n + 144.0 * worlds));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "neopipe_survey_centroids: error: " << e.what() << '\n';
    return 1;
  }
}
