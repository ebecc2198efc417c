#include "sim/target_renderer.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <optional>

#include "sim/shading.hpp"
#include "sim/table_field.hpp"

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

namespace {

// What a pixel sees of the target: its mean shade (Shades values, the board's margin and the
// workspace around it included) and the share of it that is off the board.
struct PixelSample {
  double value;
  double outside;
};

bool on_board(const CalibrationTarget& g, double s, double t) {
  const double lo = g.kind == TargetKind::dots ? -g.pitch : -2 * g.pitch;
  return !(s < lo || t < lo || s > g.cols * g.pitch || t > g.rows * g.pitch);
}

// Target coordinates of every pixel corner ((width + 1) x (height + 1), row-major): the ray
// through it (normalised coordinates from `ray_at(x - 0.5, y - 0.5)`) meets the target's plane.
template <class RayAt>
std::vector<std::optional<Eigen::Vector2d>> corner_points(const TargetPose& pose, const PinholeCamera& camera,
                                                          const RayAt& ray_at) {
  const cv::Size size = camera.size();
  const Eigen::Matrix3d rt = pose.rotation.transpose();
  const Eigen::Vector3d centre = -camera.rotation().transpose() * camera.translation();
  const Eigen::Vector3d normal = pose.rotation.col(2);
  const int cw = size.width + 1;
  std::vector<std::optional<Eigen::Vector2d>> corner(static_cast<std::size_t>(cw) * (size.height + 1));
  for (int y = 0; y <= size.height; ++y) {
    for (int x = 0; x <= size.width; ++x) {
      const Eigen::Vector2d n = ray_at(x - 0.5, y - 0.5);
      const Eigen::Vector3d dir = camera.rotation().transpose() * Eigen::Vector3d(n.x(), n.y(), 1);
      const double denom = normal.dot(dir);
      if (std::abs(denom) < 1e-12) continue;
      const double s = normal.dot(pose.translation - centre) / denom;
      if (s <= 0) continue;
      const Eigen::Vector3d local = rt * (centre + s * dir - pose.translation);
      corner[static_cast<std::size_t>(y) * cw + x] = Eigen::Vector2d(local.x(), local.y());
    }
  }
  return corner;
}

// Pixel (x, y) from its corners: a pixel no edge crosses takes its corners' shade, one an edge
// crosses is sampled kEdgeSamples^2 times, target coordinates bilinear between the corners.
PixelSample sample_pixel(const CalibrationTarget& g, const Shades& sh,
                         const std::vector<std::optional<Eigen::Vector2d>>& corner, int cw, int x, int y) {
  const auto& a = corner[static_cast<std::size_t>(y) * cw + x];
  const auto& b = corner[static_cast<std::size_t>(y) * cw + x + 1];
  const auto& c = corner[static_cast<std::size_t>(y + 1) * cw + x];
  const auto& d = corner[static_cast<std::size_t>(y + 1) * cw + x + 1];
  if (!a || !b || !c || !d) return {sh.outside, 1.0};  // looking past the target's plane
  const double va = shade(g, sh, a->x(), a->y());
  if (va == shade(g, sh, b->x(), b->y()) && va == shade(g, sh, c->x(), c->y()) && va == shade(g, sh, d->x(), d->y())) {
    return {va, on_board(g, a->x(), a->y()) ? 0.0 : 1.0};
  }
  double sum = 0;
  int off = 0;
  for (int sy = 0; sy < kEdgeSamples; ++sy) {
    const double v = (sy + 0.5) / kEdgeSamples;
    for (int sx = 0; sx < kEdgeSamples; ++sx) {
      const double u = (sx + 0.5) / kEdgeSamples;
      const Eigen::Vector2d p = (1 - v) * ((1 - u) * *a + u * *b) + v * ((1 - u) * *c + u * *d);
      sum += shade(g, sh, p.x(), p.y());
      off += on_board(g, p.x(), p.y()) ? 0 : 1;
    }
  }
  return {sum / (kEdgeSamples * kEdgeSamples), static_cast<double>(off) / (kEdgeSamples * kEdgeSamples)};
}

Shades shades_of(const CalibrationTarget& g, double background, double bright) {
  return g.kind == TargetKind::dots ? Shades{background, background * 0.5, bright}
                                    : Shades{background, bright, background * 0.6};
}

// The target's light under ImageModel settings: flat shades, as it has always been rendered.
cv::Mat flat_light(const CalibrationTarget& g, const TargetPose& pose, const PinholeCamera& camera, const Shades& sh) {
  const cv::Size size = camera.size();
  const auto corner = corner_points(pose, camera, [&](double u, double v) { return camera.undistort({u, v}); });
  cv::Mat light(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    auto* row = light.ptr<float>(y);
    for (int x = 0; x < size.width; ++x)
      row[x] = static_cast<float>(sample_pixel(g, sh, corner, size.width + 1, x, y).value);
  }
  return light;
}

}  // namespace

cv::Mat render_target(const CalibrationTarget& g, const TargetPose& pose, const PinholeCamera& camera,
                      const MarbleRenderer& renderer, std::int64_t frame) {
  const ImageModel& m = renderer.model();
  return renderer.expose(flat_light(g, pose, camera, shades_of(g, m.background, m.marble)), frame);
}

cv::Mat render_target(const CalibrationTarget& g, const TargetPose& pose, const PinholeCamera& camera,
                      const SceneRenderer& renderer, std::int64_t frame) {
  return renderer.expose(target_light(g, pose, camera, renderer), frame);
}

cv::Mat target_light(const CalibrationTarget& g, const TargetPose& pose, const PinholeCamera& camera,
                     const SceneRenderer& renderer) {
  const Rendering& r = renderer.rendering();
  const Shades sh = shades_of(g, r.surfaces.table, r.surfaces.marble);
  if (r.is_image_model()) return flat_light(g, pose, camera, sh);

  // The printed face (matte) lit by the light at its own angle; around the board, the table.
  const cv::Size size = camera.size();
  const RayTable& rays = renderer.rays();
  const auto corner = corner_points(pose, camera, [&](double u, double v) { return rays.interpolate(u, v); });
  const TableField table = renderer.table(camera);
  std::optional<Shader> shader;
  if (r.light) shader.emplace(*r.light, r.light->position, r.light->position.z());
  const Eigen::Vector3d normal = pose.rotation.col(2);
  const int cw = size.width + 1;
  cv::Mat light(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    auto* row = light.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const PixelSample p = sample_pixel(g, sh, corner, cw, x, y);
      double board = p.value - p.outside * sh.outside;  // the board's shades times its share
      if (board > 0 && shader) {
        // Lit at the pixel's centre on the board: the light changes little across a pixel.
        Eigen::Vector2d mid = Eigen::Vector2d::Zero();
        for (const int dy : {0, 1}) {
          for (const int dx : {0, 1}) mid += *corner[static_cast<std::size_t>(y + dy) * cw + x + dx] / 4;
        }
        const Eigen::Vector3d at = pose.rotation * Eigen::Vector3d(mid.x(), mid.y(), 0) + pose.translation;
        board *= shader->lit(shader->direct(at, normal));
      }
      row[x] = static_cast<float>(board + p.outside * table.at(x, y));
    }
  }
  return light;
}

}  // namespace neopipe::sim
