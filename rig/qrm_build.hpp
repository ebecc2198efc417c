#pragma once
// QRM map building as spec qrm.md §10 runs it: one world, N random imaging positions, the panorama
// at each fused into a fresh map (rig/qrm_imaging.hpp), the metrics M1-M5 after every image against
// the truth (rig/qrm_metrics.hpp); and the Monte Carlo of many such runs over several k, run in
// parallel (one run per task, each deterministic for its seed).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "rig/qrm_imaging.hpp"
#include "rig/qrm_metrics.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

struct QrmBuildSettings {
  std::size_t images = 50;
  std::size_t nearest = 18;      ///< k
  double bearing_noise_deg = 0;  ///< the sensor's configured bearing noise (sd)
  double sensor_range_mm = 600;  ///< R_s (the default sees the whole 500 mm workspace)
  std::uint64_t seed = 1;        ///< positions, zero directions and noise: streams of it (rig/seeds.hpp)
};

/// One image and the map after it.
struct QrmBuildStep {
  QrmImageReport image;
  QrmMetrics metrics;
  /// M5: microseconds per update (measuring one triple and fusing it), this image's mean.
  double m5_us = 0;
};

struct QrmBuildResult {
  std::vector<Eigen::Vector2d> positions;
  std::vector<QrmBuildStep> steps;
  RngEdges true_rng;
  int inconsistencies = 0;  ///< measurements rolled back over the run
};

/// The imaging settings a build uses (the sensor's noise seeded by stream panorama of `seed`, the
/// zero directions by stream qrm_headings).
QrmImagingSettings qrm_imaging_settings(const QrmBuildSettings& settings);
/// The imaging positions of a build (stream qrm_positions of `seed`).
std::vector<Eigen::Vector2d> qrm_imaging_positions(const sim::World& world, const QrmBuildSettings& settings);

/// Builds a map of `world` from settings.images images; `on_image(done)` after each. Throws
/// std::invalid_argument for fewer than 3 marbles or k < 3, nav::qrm::DegenerateTripleError for a
/// degenerate true triple.
QrmBuildResult build_qrm_map(const sim::World& world, const QrmBuildSettings& settings,
                             const std::function<void(std::size_t)>& on_image = {});

/// Spec §10's Monte Carlo: `runs` worlds of `marbles` marbles uniform in the workspace (redrawn while
/// degenerate), each imaged at the same random positions for every k of `nearest`.
struct QrmExperimentSettings {
  std::size_t runs = 100;
  std::size_t marbles = 30;
  std::vector<std::size_t> nearest{6, 12, 18, 24, 30};
  QrmBuildSettings build;  ///< images, noise, range, seed (its k is replaced by each of `nearest`)
};

/// One (run, k, image) row.
struct QrmExperimentRow {
  std::size_t run = 0;
  std::size_t nearest = 0;
  std::size_t image = 0;  ///< 1-based: the map after this many images
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0, m5_us = 0;
  std::size_t triples = 0;
  std::size_t inconsistent = 0;
  std::size_t lost = 0;
  double rng_precision = 0, rng_recall = 0;
  bool rng_equal = false;
};

/// Rows in (run, k, image) order whatever the threads did. `on_run()` after each run (any thread).
std::vector<QrmExperimentRow> run_qrm_experiment(const QrmExperimentSettings& settings,
                                                 const std::function<void()>& on_run = {});

}  // namespace neopipe::rig
