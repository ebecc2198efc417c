// Simulator rendering speed: onboard 256x256 frames along a path over a default world (the
// navigator renders thousands of them per batch of journeys), one core, at the ideal realism
// (today's MarbleRenderer) and at rig (SceneRenderer: spheres, light, shadows, texture, lens,
// defocus, shot noise), beside a peer that draws the same marbles with OpenCV (anti-aliased
// circles, Gaussian blur, cv::randn noise); and global 1280x960 frames at rig.
//   ./build/bench/neopipe_sim_bench --benchmark_min_time=0.5
// items_per_second is frames/s.

#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/realism.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace {
namespace sim = neopipe::sim;

sim::World world(int objects) {
  sim::WorldRequest q;
  q.objects = objects;
  q.seed = 11;
  return sim::generate_world(q);
}

// Poses on a slow loop over the workspace, so frames see 0, 1 or several marbles as a journey does.
sim::Pose2 pose_at(std::int64_t i) {
  const double t = static_cast<double>(i % 10000) / 10000 * 6.283185307179586;
  return {250 + 180 * std::cos(3 * t), 250 + 180 * std::sin(2 * t), t};
}

void BM_OnboardFrame(benchmark::State& state) {
  const sim::World w = world(static_cast<int>(state.range(0)));
  const sim::OnboardCameraConfig config;
  const sim::MarbleRenderer renderer(sim::ImageModel{}, {config.side_px, config.side_px});
  std::int64_t i = 0;
  for (auto _ : state) {
    const auto camera = sim::make_onboard_camera(pose_at(i), config);
    benchmark::DoNotOptimize(renderer.render(w.objects, w.marble_diameter, camera, i).data);
    ++i;
  }
  state.SetItemsProcessed(i);
}

// The rig's onboard camera: the window in the plane of the marbles' centres, the rig lens placed
// per frame (onboard_camera_at), the renderer built once.
void BM_OnboardFrameRig(benchmark::State& state) {
  const sim::World w = world(static_cast<int>(state.range(0)));
  const sim::Rendering rig = sim::rendering_for(sim::Realism::rig, sim::CameraKind::onboard);
  const sim::OnboardCameraConfig config = sim::onboard_config_for(rig, w.marble_diameter);
  const sim::Intrinsics k = sim::onboard_intrinsics(config, rig);
  const sim::SceneRenderer renderer(rig, sim::onboard_camera_at(pose_at(0), config, k));
  std::int64_t i = 0;
  for (auto _ : state) {
    const auto camera = sim::onboard_camera_at(pose_at(i), config, k);
    benchmark::DoNotOptimize(renderer.render(w.objects, w.marble_diameter, camera, i).data);
    ++i;
  }
  state.SetItemsProcessed(i);
}

// The global camera at rig: it never moves, so the table's light is the renderer's cache.
void BM_GlobalFrameRig(benchmark::State& state) {
  const sim::World w = world(static_cast<int>(state.range(0)));
  const sim::Rendering rig = sim::rendering_for(sim::Realism::rig, sim::CameraKind::global);
  const auto camera = sim::make_global_camera(w.size, {}, rig);
  const sim::SceneRenderer renderer(rig, camera);
  std::int64_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.render(w.objects, w.marble_diameter, camera, i).data);
    ++i;
  }
  state.SetItemsProcessed(i);
}

// The peer: what a user would write with OpenCV for the same frame (no shading, no area-exact rim).
void BM_OnboardFrameOpenCV(benchmark::State& state) {
  const sim::World w = world(static_cast<int>(state.range(0)));
  const sim::OnboardCameraConfig config;
  const sim::ImageModel model;
  cv::RNG rng(1);
  std::int64_t i = 0;
  cv::Mat noise(config.side_px, config.side_px, CV_8S);
  for (auto _ : state) {
    const auto camera = sim::make_onboard_camera(pose_at(i), config);
    cv::Mat img(config.side_px, config.side_px, CV_8U, cv::Scalar(model.background));
    for (const auto& p : w.objects) {
      const auto c = camera.project({p.x(), p.y(), 0});
      if (!c || c->x() < -20 || c->y() < -20 || c->x() > config.side_px + 20 || c->y() > config.side_px + 20) continue;
      constexpr int kShift = 4;
      cv::circle(img, {static_cast<int>(c->x() * 16), static_cast<int>(c->y() * 16)},
                 static_cast<int>(w.marble_diameter / 2 * config.side_px / config.window_mm * 16),
                 cv::Scalar(model.marble), cv::FILLED, cv::LINE_AA, kShift);
    }
    cv::GaussianBlur(img, img, cv::Size(0, 0), model.blur_sigma);
    rng.fill(noise, cv::RNG::NORMAL, 0, model.noise_sigma);
    cv::add(img, noise, img, cv::noArray(), CV_8U);
    benchmark::DoNotOptimize(img.data);
    ++i;
  }
  state.SetItemsProcessed(i);
}

}  // namespace

BENCHMARK(BM_OnboardFrame)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OnboardFrameRig)->Arg(0)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);  // 0: the fixed cost
BENCHMARK(BM_GlobalFrameRig)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OnboardFrameOpenCV)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
