#include "rig/qrm_build.hpp"

#include <tbb/parallel_for.h>

#include <stdexcept>

#include "nav/qrm/relational_map.hpp"
#include "rig/seeds.hpp"

namespace neopipe::rig {

QrmImagingSettings qrm_imaging_settings(const QrmBuildSettings& settings) {
  QrmImagingSettings imaging;
  imaging.sensor.range_mm = settings.sensor_range_mm;
  imaging.sensor.bearing_noise_deg = settings.bearing_noise_deg;
  imaging.sensor.seed = stream_seed(settings.seed, streams::panorama);
  imaging.heading_seed = stream_seed(settings.seed, streams::qrm_headings);
  imaging.observation.nearest = settings.nearest;
  return imaging;
}

std::vector<Eigen::Vector2d> qrm_imaging_positions(const sim::World& world, const QrmBuildSettings& settings) {
  return random_imaging_positions(world, settings.images, stream_seed(settings.seed, streams::qrm_positions));
}

namespace {

QrmBuildResult build_with_truth(const sim::World& world, const QrmTruth& truth, const QrmBuildSettings& settings,
                                std::vector<Eigen::Vector2d> positions,
                                const std::function<void(std::size_t)>& on_image) {
  if (settings.nearest < 3) throw std::invalid_argument("qrm build: k must be at least 3");
  QrmBuildResult result;
  result.positions = std::move(positions);
  result.true_rng = truth.rng();
  QrmImaging imaging(world, qrm_imaging_settings(settings));
  nav::qrm::RelationalMap map;
  result.steps.reserve(result.positions.size());
  for (const Eigen::Vector2d& p : result.positions) {
    QrmBuildStep step;
    step.image = imaging.image(map, p);
    step.metrics = truth.metrics(map);
    step.m5_us = step.image.fused.triples == 0
                     ? 0
                     : 1e6 * step.image.fuse_seconds / static_cast<double>(step.image.fused.triples);
    result.inconsistencies += static_cast<int>(step.image.fused.inconsistent);
    result.steps.push_back(std::move(step));
    if (on_image) on_image(result.steps.size());
  }
  return result;
}

}  // namespace

QrmBuildResult build_qrm_map(const sim::World& world, const QrmBuildSettings& settings,
                             const std::function<void(std::size_t)>& on_image) {
  if (world.objects.size() < 3) throw std::invalid_argument("qrm build: a map needs at least 3 marbles");
  const QrmTruth truth(world.objects);
  return build_with_truth(world, truth, settings, qrm_imaging_positions(world, settings), on_image);
}

std::vector<QrmExperimentRow> run_qrm_experiment(const QrmExperimentSettings& settings,
                                                 const std::function<void()>& on_run) {
  if (settings.marbles < 3) throw std::invalid_argument("qrm experiment: worlds need at least 3 marbles");
  if (settings.nearest.empty()) throw std::invalid_argument("qrm experiment: no k given");
  const std::size_t per_run = settings.nearest.size() * settings.build.images;
  std::vector<QrmExperimentRow> rows(settings.runs * per_run);
  // One task per run: runs share nothing, and each writes only its own rows, so the result does not
  // depend on the schedule (only the M5 timings do).
  tbb::parallel_for(std::size_t{0}, settings.runs, [&](std::size_t run) {
    const std::uint64_t seed = trial_seed(settings.build.seed, static_cast<std::int64_t>(run));
    sim::WorldRequest request;
    request.objects = static_cast<int>(settings.marbles);
    request.seed = stream_seed(seed, streams::qrm_world);
    const sim::World world = generate_qrm_world(request);
    const QrmTruth truth(world.objects);
    QrmBuildSettings build = settings.build;
    build.seed = seed;
    const std::vector<Eigen::Vector2d> positions = qrm_imaging_positions(world, build);
    for (std::size_t ki = 0; ki < settings.nearest.size(); ++ki) {
      build.nearest = settings.nearest[ki];
      const QrmBuildResult r = build_with_truth(world, truth, build, positions, {});
      for (std::size_t i = 0; i < r.steps.size(); ++i) {
        const QrmBuildStep& s = r.steps[i];
        QrmExperimentRow& row = rows[run * per_run + ki * settings.build.images + i];
        row.run = run;
        row.nearest = build.nearest;
        row.image = i + 1;
        row.m1 = s.metrics.m1;
        row.m2 = s.metrics.m2;
        row.m3 = s.metrics.m3;
        row.m4 = s.metrics.m4;
        row.m5_us = s.m5_us;
        row.triples = s.image.fused.triples;
        row.inconsistent = s.image.fused.inconsistent;
        row.lost = s.metrics.lost;
        row.rng_precision = s.metrics.versus_truth.precision;
        row.rng_recall = s.metrics.versus_truth.recall;
        row.rng_equal = s.metrics.versus_truth.equal;
      }
    }
    if (on_run) on_run();
  });
  return rows;
}

}  // namespace neopipe::rig
