#pragma once
// What the realism tests share: one-marble worlds, settings with every effect off but the ones a
// test looks at, the engine's blob graph, and area-sampled references built without the renderer's
// machinery (camera.undistort and ray-sphere tests per sub-pixel sample).

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/kernel_registry.hpp"
#include "sim/cameras.hpp"
#include "sim/realism.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace rig_test {

namespace sim = neopipe::sim;
namespace pl = neopipe::pipeline;

inline sim::World one_marble(const Eigen::Vector2d& at, double diameter = 5) {
  sim::World w;
  w.size = {500, 500};
  w.marble_diameter = diameter;
  w.objects = {at};
  return w;
}

/// `r` with the sensor, blur, texture and vignetting off: the light reaching the sensor, exactly.
inline sim::Rendering quiet(sim::Rendering r) {
  r.surfaces.texture = 0;
  r.defocus = {0, 0};
  r.sensor.read_noise = 0;
  r.sensor.full_well.reset();
  r.sensor.prnu = 0;
  r.sensor.vignetting = 0;
  r.sensor.gradient = 0;
  r.interlace = false;
  return r;
}

/// A random world of `objects` marbles on the default 500 x 500 mm workspace.
inline sim::World world(int objects, std::uint64_t seed) {
  sim::WorldRequest q;
  q.objects = objects;
  q.seed = seed;
  return sim::generate_world(q);
}

inline sim::Rendering rig(sim::CameraKind kind) {
  return sim::rendering_for(sim::Realism::rig, kind);
}

/// The rig's onboard camera (window at the marbles' centres, rig lens) at `pose`.
inline sim::PinholeCamera onboard(const sim::Rendering& r, const sim::Pose2& pose, double diameter = 5) {
  return sim::make_onboard_camera(pose, sim::onboard_config_for(r, diameter), r);
}

/// The engine's blob graph on one frame: a fixed threshold, or Otsu's per frame.
inline pl::BlobList blobs(const cv::Mat& frame, std::optional<int> threshold) {
  pl::BlobGraphOptions options;
  options.threshold = threshold;
  options.source = pl::PortType::gray8;
  const auto results = pl::run_frames(pl::compile(pl::blob_graph(options), pl::standard_kernels()), {frame});
  return std::get<pl::BlobList>(results.at(0).outputs.at(0));
}

/// The engine's marble graph (examples/marbles.yaml): blobs of gray - level, weighted by it.
inline pl::BlobList marble_blobs(const cv::Mat& frame, int level) {
  const auto results = pl::run_frames(pl::compile(pl::marble_graph(level), pl::standard_kernels()), {frame});
  return std::get<pl::BlobList>(results.at(0).outputs.at(0));
}

/// Whether the ray from the camera's centre along world direction `dir` meets the sphere.
inline bool ray_hits(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Eigen::Vector3d& centre,
                     double r) {
  const Eigen::Vector3d w = centre - origin;
  const double along = w.dot(dir) / dir.squaredNorm();
  return along > 0 && (w - along * dir).squaredNorm() < r * r;
}

/// The world direction of the ray through sub-pixel (u, v), by the camera's own undistortion.
inline Eigen::Vector3d ray_through(const sim::PinholeCamera& cam, double u, double v) {
  const Eigen::Vector2d n = cam.undistort({u, v});
  return cam.rotation().transpose() * Eigen::Vector3d(n.x(), n.y(), 1);
}

/// The fraction of each pixel of `box` covered by the sphere, by `n` x `n` samples per pixel
/// (sampled finely only where a coarse 4 x 4 pass finds the rim in the pixel or a neighbour: a
/// sliver in a corner can slip between the coarse samples, never past a whole pixel).
inline cv::Mat supersampled_coverage(const sim::PinholeCamera& cam, const Eigen::Vector3d& centre, double r,
                                     const cv::Rect& box, int n) {
  cv::Mat cover(box.size(), CV_64F);
  const Eigen::Vector3d origin = cam.centre();
  const auto fraction = [&](int x, int y, int samples) {
    int in = 0;
    for (int sy = 0; sy < samples; ++sy) {
      for (int sx = 0; sx < samples; ++sx) {
        const double u = x - 0.5 + (sx + 0.5) / samples;
        const double v = y - 0.5 + (sy + 0.5) / samples;
        in += ray_hits(origin, ray_through(cam, u, v), centre, r) ? 1 : 0;
      }
    }
    return static_cast<double>(in) / (samples * samples);
  };
  cv::Mat coarse(box.size(), CV_64F);
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) coarse.at<double>(y, x) = fraction(box.x + x, box.y + y, 4);
  }
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      bool rim = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int yy = std::clamp(y + dy, 0, box.height - 1);
          const int xx = std::clamp(x + dx, 0, box.width - 1);
          const double c = coarse.at<double>(yy, xx);
          rim = rim || (c != coarse.at<double>(y, x)) || (c > 0 && c < 1);
        }
      }
      cover.at<double>(y, x) = rim ? fraction(box.x + x, box.y + y, n) : coarse.at<double>(y, x);
    }
  }
  return cover;
}

/// The centroid (px) of a non-negative weight image whose top-left pixel is `origin`.
inline Eigen::Vector2d centroid(const cv::Mat& weights, const cv::Point& origin) {
  cv::Mat w;
  weights.convertTo(w, CV_64F);
  double sum = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  for (int y = 0; y < w.rows; ++y) {
    for (int x = 0; x < w.cols; ++x) {
      const double v = w.at<double>(y, x);
      sum += v;
      at += v * Eigen::Vector2d(origin.x + x, origin.y + y);
    }
  }
  return at / sum;
}

}  // namespace rig_test
