#include "sim/target_renderer.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <optional>

namespace neopipe::sim {
namespace {

constexpr int kEdgeSamples = 8;  // per axis, in a pixel that an edge crosses

struct Shades {
  double outside;  // the workspace around the board
  double board;    // paper, or the dots' board
  double mark;     // the dots, or the black squares
};

// The light at target point (s, t): board with a margin of one pitch around the pattern.
double shade(const CalibrationTarget& g, const Shades& sh, double s, double t) {
  // The board: the pattern and a margin of one pitch all round (for a chessboard, from its first inner
  // corner, one square of pattern and one of margin).
  const double lo = g.kind == TargetKind::dots ? -g.pitch : -2 * g.pitch;
  const double hi_s = g.cols * g.pitch;
  const double hi_t = g.rows * g.pitch;
  if (s < lo || t < lo || s > hi_s || t > hi_t) return sh.outside;
  if (g.kind == TargetKind::dots) {
    const double i = std::round(s / g.pitch);
    const double j = std::round(t / g.pitch);
    if (i < 0 || j < 0 || i >= g.cols || j >= g.rows) return sh.board;
    const double ds = s - i * g.pitch;
    const double dt = t - j * g.pitch;
    return ds * ds + dt * dt < g.dot_diameter * g.dot_diameter / 4 ? sh.mark : sh.board;
  }
  // The target's origin is its first inner corner: the squares start a pitch before it.
  s += g.pitch;
  t += g.pitch;
  if (s < 0 || t < 0 || s >= g.cols * g.pitch || t >= g.rows * g.pitch) return sh.board;  // the white margin
  const auto i = static_cast<long>(std::floor(s / g.pitch));
  const auto j = static_cast<long>(std::floor(t / g.pitch));
  return (i + j) % 2 == 0 ? sh.mark : sh.board;
}

}  // namespace

TargetPose target_pose(double x, double y, double z, double theta_deg, double tilt_x_deg, double tilt_y_deg) {
  constexpr double deg = std::numbers::pi / 180;
  TargetPose p;
  p.rotation = (Eigen::AngleAxisd(theta_deg * deg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(tilt_x_deg * deg, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(tilt_y_deg * deg, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  p.translation = {x, y, z};
  return p;
}

std::vector<Eigen::Vector2d> target_points(const CalibrationTarget& g) {
  std::vector<Eigen::Vector2d> out;
  const bool dots = g.kind == TargetKind::dots;
  const int cols = dots ? g.cols : g.cols - 1;
  const int rows = dots ? g.rows : g.rows - 1;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) out.emplace_back(i * g.pitch, j * g.pitch);
  }
  return out;
}

std::vector<Eigen::Vector2d> projected_target_points(const CalibrationTarget& target, const TargetPose& pose,
                                                     const PinholeCamera& camera) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : target_points(target)) {
    const auto px = camera.project(pose.rotation * Eigen::Vector3d(p.x(), p.y(), 0) + pose.translation);
    out.push_back(px ? *px : Eigen::Vector2d(NAN, NAN));
  }
  return out;
}

cv::Mat render_target(const CalibrationTarget& g, const TargetPose& pose, const PinholeCamera& camera,
                      const MarbleRenderer& renderer, std::int64_t frame) {
  const ImageModel& m = renderer.model();
  const Shades sh = g.kind == TargetKind::dots ? Shades{m.background, m.background * 0.5, m.marble}
                                               : Shades{m.background, m.marble, m.background * 0.6};
  const cv::Size size = camera.size();
  // Target coordinates of every pixel corner: the ray through it meets the target's plane.
  const Eigen::Matrix3d rt = pose.rotation.transpose();
  const Eigen::Vector3d centre = -camera.rotation().transpose() * camera.translation();
  const Eigen::Vector3d normal = pose.rotation.col(2);
  const int cw = size.width + 1;
  std::vector<std::optional<Eigen::Vector2d>> corner(static_cast<std::size_t>(cw) * (size.height + 1));
  for (int y = 0; y <= size.height; ++y) {
    for (int x = 0; x <= size.width; ++x) {
      const Eigen::Vector2d n = camera.undistort({x - 0.5, y - 0.5});
      const Eigen::Vector3d dir = camera.rotation().transpose() * Eigen::Vector3d(n.x(), n.y(), 1);
      const double denom = normal.dot(dir);
      if (std::abs(denom) < 1e-12) continue;
      const double s = normal.dot(pose.translation - centre) / denom;
      if (s <= 0) continue;
      const Eigen::Vector3d local = rt * (centre + s * dir - pose.translation);
      corner[static_cast<std::size_t>(y) * cw + x] = Eigen::Vector2d(local.x(), local.y());
    }
  }
  cv::Mat light(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    auto* row = light.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const auto& a = corner[static_cast<std::size_t>(y) * cw + x];
      const auto& b = corner[static_cast<std::size_t>(y) * cw + x + 1];
      const auto& c = corner[static_cast<std::size_t>(y + 1) * cw + x];
      const auto& d = corner[static_cast<std::size_t>(y + 1) * cw + x + 1];
      if (!a || !b || !c || !d) {
        row[x] = static_cast<float>(sh.outside);  // looking past the target's plane
        continue;
      }
      const double va = shade(g, sh, a->x(), a->y());
      if (va == shade(g, sh, b->x(), b->y()) && va == shade(g, sh, c->x(), c->y()) &&
          va == shade(g, sh, d->x(), d->y())) {
        row[x] = static_cast<float>(va);
        continue;
      }
      // An edge crosses the pixel: sample it, the target coordinates bilinear between the corners.
      double sum = 0;
      for (int sy = 0; sy < kEdgeSamples; ++sy) {
        const double v = (sy + 0.5) / kEdgeSamples;
        for (int sx = 0; sx < kEdgeSamples; ++sx) {
          const double u = (sx + 0.5) / kEdgeSamples;
          const Eigen::Vector2d p = (1 - v) * ((1 - u) * *a + u * *b) + v * ((1 - u) * *c + u * *d);
          sum += shade(g, sh, p.x(), p.y());
        }
      }
      row[x] = static_cast<float>(sum / (kEdgeSamples * kEdgeSamples));
    }
  }
  return renderer.expose(light, frame);
}

}  // namespace neopipe::sim
