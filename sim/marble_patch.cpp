#include "sim/marble_patch.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/marble_renderer.hpp"

namespace neopipe::sim {
namespace {

using Eigen::Vector3d;

// The distance (mm) of the line through the origin along d (dd = d.d) from `centre`, less r; a
// centre behind the camera: its distance from the camera. Continuous either way.
double sphere_distance(const Vector3d& d, double dd, const Vector3d& centre, double r) {
  if (d.dot(centre) <= 0) return centre.norm() - r;
  return std::sqrt(d.cross(centre).squaredNorm() / dd) - r;
}

// Of the ray from table point p towards the light: its distance from the sphere, less r. A sphere
// on the far side of p from the light cannot shadow it: then p's distance from the sphere, which
// the line's distance becomes where the two cases meet, so the function stays continuous.
double shadow_distance(const Vector3d& p, const Vector3d& light, const Vector3d& centre, double r) {
  const Vector3d u = light - p;
  const Vector3d w = centre - p;
  if (w.dot(u) <= 0) return w.norm() - r;
  return std::sqrt(w.cross(u).squaredNorm() / u.squaredNorm()) - r;
}

// Whether the segment from surface point x to the light passes through a sphere.
bool blocks(const Vector3d& x, const Vector3d& light, const Vector3d& centre, double r) {
  const Vector3d u = light - x;
  const Vector3d w = centre - x;
  return w.dot(u) > 0 && w.cross(u).squaredNorm() < r * r * u.squaredNorm();
}

// The fraction of pixel `i` of a distance grid (row stride `stride`) on the negative side: the
// straight edge through the pixel's gradient (central differences), box-filtered exactly.
double coverage(const float* grid, std::size_t i, std::size_t stride) {
  const double v = grid[i];
  const double gx = 0.5 * (static_cast<double>(grid[i + 1]) - grid[i - 1]);
  const double gy = 0.5 * (static_cast<double>(grid[i + stride]) - grid[i - stride]);
  const double gn = std::sqrt(gx * gx + gy * gy);
  // Half a pixel's diagonal (0.71) from the edge decides without the exact area.
  if (v >= 0.75 * gn) return 0;
  if (v <= -0.75 * gn) return 1;
  return pixel_coverage(-v / gn, gx / gn, gy / gn);
}

// The gradient's length (mm per pixel) at pixel i of a grid.
double gradient_length(const float* grid, std::size_t i, std::size_t stride) {
  const double gx = 0.5 * (static_cast<double>(grid[i + 1]) - grid[i - 1]);
  const double gy = 0.5 * (static_cast<double>(grid[i + stride]) - grid[i - stride]);
  return std::sqrt(gx * gx + gy * gy);
}

// Light leaving sphere k towards the camera along ray d: at the point the ray meets it, or where it
// passes closest (a rim pixel whose centre misses).
double sphere_light(const PatchContext& c, std::span<const Vector3d> centres, std::size_t k, const Vector3d& d,
                    double dd) {
  const double r = c.radius;
  const double albedo = c.rendering.surfaces.marble;
  if (!c.shader) return albedo;
  const Vector3d& s = centres[k];
  const double t0 = d.dot(s) / dd;
  const Vector3d off = t0 * d - s;
  const double off2 = off.squaredNorm();
  const Vector3d x = off2 < r * r ? Vector3d((t0 - std::sqrt((r * r - off2) / dd)) * d)
                                  : Vector3d(s + off * (r / std::sqrt(std::max(off2, 1e-300))));
  const Vector3d n = (x - s) / r;
  const Shader& shader = *c.shader;
  if (c.rendering.light->shadows) {
    for (std::size_t j = 0; j < centres.size(); ++j) {
      if (j != k && blocks(x, shader.position(), centres[j], r)) return albedo * shader.lit(0);
    }
  }
  return albedo * shader.lit(shader.direct(x, n)) + shader.highlight(x, n);
}

// A disk's light (MarbleRenderer's dome) at table point p, `cover` of the pixel inside its rim.
double disk_light(const PatchContext& c, const Vector3d& centre, const Vector3d& p, double cover, double grad_mm) {
  const Surfaces& s = c.rendering.surfaces;
  const double r = c.radius;
  double rho = (p - centre).norm() / r;
  if (cover < 1) rho = std::max(0.0, 1 - 0.5 * cover * grad_mm / r);  // halfway into the covered part
  const double dome = s.disk_rim + (1 - s.disk_rim) * std::sqrt(std::max(0.0, 1 - rho * rho));
  const double light = c.shader ? c.shader->lit(c.shader->table_direct(p)) : 1.0;
  return (s.table + (s.marble - s.table) * dome) * light;
}

}  // namespace

cv::Mat marble_patch(const PatchContext& c, std::span<const Vector3d> centres, const cv::Rect& rect) {
  const bool sphere = c.rendering.shape == MarbleShape::sphere;
  const bool shadows = sphere && c.shader && c.rendering.light->shadows;
  const double r = c.radius;
  const std::size_t n = centres.size();
  // Distance grids with a one-pixel border for the central differences: the silhouettes', and the
  // shadows' on the table.
  const std::size_t gw = static_cast<std::size_t>(rect.width) + 2;
  const std::size_t gh = static_cast<std::size_t>(rect.height) + 2;
  const std::size_t cells = gw * gh;
  std::vector<float> outline(n * cells);
  std::vector<float> shade(shadows ? n * cells : 0);
  constexpr float kNowhere = 1e3F;  // mm: a ray that meets no table
  const Vector3d light = c.shader ? c.shader->position() : Vector3d::Zero();
  for (std::size_t gy = 0; gy < gh; ++gy) {
    const int py = rect.y - 1 + static_cast<int>(gy);
    for (std::size_t gx = 0; gx < gw; ++gx) {
      const Eigen::Vector2d ray = c.rays.at(rect.x - 1 + static_cast<int>(gx), py);
      const Vector3d d(ray.x(), ray.y(), 1);
      const double dd = d.squaredNorm();
      const std::size_t i = gy * gw + gx;
      const auto p = (shadows || !sphere) ? c.geometry.table_point(ray) : std::nullopt;
      for (std::size_t k = 0; k < n; ++k) {
        if (sphere) {
          outline[k * cells + i] = static_cast<float>(sphere_distance(d, dd, centres[k], r));
        } else {
          outline[k * cells + i] = p ? static_cast<float>((*p - centres[k]).norm() - r) : kNowhere;
        }
        if (shadows)
          shade[k * cells + i] = p ? static_cast<float>(shadow_distance(*p, light, centres[k], r)) : kNowhere;
      }
    }
  }

  cv::Mat patch = cv::Mat::zeros(rect.size(), CV_32F);
  for (int y = 0; y < rect.height; ++y) {
    auto* out = patch.ptr<float>(y);
    for (int x = 0; x < rect.width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) + 1) * gw + static_cast<std::size_t>(x) + 1;
      // Most of a patch is bare table in full light: leave it at zero change.
      bool near = false;
      for (std::size_t k = 0; k < n && !near; ++k) {
        near = outline[k * cells + i] < 0.75 * gradient_length(&outline[k * cells], i, gw) ||
               (shadows && shade[k * cells + i] < 0.75 * gradient_length(&shade[k * cells], i, gw));
      }
      if (!near) continue;
      const Eigen::Vector2d ray = c.rays.at(rect.x + x, rect.y + y);
      const Vector3d d(ray.x(), ray.y(), 1);
      const double dd = d.squaredNorm();
      const auto p = c.geometry.table_point(ray);
      double covered = 0;  // of the pixel, by marbles
      double marble_light = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const double cover = coverage(&outline[k * cells], i, gw);
        if (cover <= 0) continue;
        covered += cover;
        if (sphere) {
          marble_light += cover * sphere_light(c, centres, k, d, dd);
        } else if (p) {
          marble_light += cover * disk_light(c, centres[k], *p, cover, gradient_length(&outline[k * cells], i, gw));
        }
      }
      covered = std::min(covered, 1.0);
      const double table = c.table.at(rect.x + x, rect.y + y);
      double table_light = table;
      if (shadows && p) {
        double lit = 1;  // the part of the pixel's table that sees the light
        for (std::size_t k = 0; k < n; ++k) lit *= 1 - coverage(&shade[k * cells], i, gw);
        if (lit < 1) {
          // Only the direct light is stopped: the table keeps its ambient share.
          const Shader& s = *c.shader;
          const double direct = (1 - s.light().ambient) * s.table_direct(*p);
          table_light *= 1 - (1 - lit) * direct / (s.light().ambient + direct);
        }
      }
      out[x] = static_cast<float>(marble_light + (1 - covered) * table_light - table);
    }
  }
  return patch;
}

}  // namespace neopipe::sim
