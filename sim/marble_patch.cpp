#include "sim/marble_patch.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/marble_renderer.hpp"

namespace neopipe::sim {
namespace {

using Eigen::Vector3d;

// Whether the segment from surface point x to the light passes through a sphere.
bool blocks(const Vector3d& x, const Vector3d& light, const Vector3d& centre, double r) {
  const Vector3d u = light - x;
  const Vector3d w = centre - x;
  return w.dot(u) > 0 && w.cross(u).squaredNorm() < r * r * u.squaredNorm();
}

// A distance grid (mm per cell, rows of `stride`) and the least distance from which no pixel can
// be touched: half a pixel's diagonal times the steepest change between neighbours.
struct Grid {
  const float* cells;
  std::size_t stride;
  float far;
};

float far_bound(const float* g, std::size_t w, std::size_t h) {
  float steepest = 0;
  for (std::size_t y = 0; y + 1 < h; ++y) {
    const float* row = g + y * w;
    const float* below = row + w;
    for (std::size_t x = 0; x + 1 < w; ++x) steepest = std::max(steepest, std::abs(row[x + 1] - row[x]));
    for (std::size_t x = 0; x < w; ++x) steepest = std::max(steepest, std::abs(below[x] - row[x]));
  }
  return 0.75F * 1.4143F * steepest;
}

// The gradient (mm per pixel) at cell i, by central differences.
Eigen::Vector2d gradient(const Grid& g, std::size_t i) {
  return {0.5 * (static_cast<double>(g.cells[i + 1]) - g.cells[i - 1]),
          0.5 * (static_cast<double>(g.cells[i + g.stride]) - g.cells[i - g.stride])};
}

// The part [a, b] of the line {p : p.n = s} (t along it from its point nearest the pixel's centre)
// inside the unit pixel centred on the origin.
std::pair<double, double> chord(double s, const Eigen::Vector2d& n) {
  const Eigen::Vector2d foot = s * n;
  const Eigen::Vector2d along(-n.y(), n.x());
  double a = -1e9;
  double b = 1e9;
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(along[axis]) < 1e-12) continue;
    const double t0 = (-0.5 - foot[axis]) / along[axis];
    const double t1 = (0.5 - foot[axis]) / along[axis];
    a = std::max(a, std::min(t0, t1));
    b = std::min(b, std::max(t0, t1));
  }
  return {a, std::max(a, b)};
}

// The fraction of cell i's pixel on the negative side: the straight edge through the pixel along
// its gradient, box-filtered exactly, less the sliver between that tangent line and the curved
// outline (curvature from the grid's second differences: the outline leaves the tangent by
// curvature x t^2 / 2 at t along it, so over the chord [a, b] the sliver is curvature (b^3 - a^3) / 6).
double coverage(const Grid& g, std::size_t i) {
  const double v = g.cells[i];
  if (v >= g.far) return 0;
  if (v <= -g.far) return 1;
  const Eigen::Vector2d grad = gradient(g, i);
  const double gn = grad.norm();
  // Half a pixel's diagonal (0.71) from the edge decides without the exact area.
  if (v >= 0.75 * gn) return 0;
  if (v <= -0.75 * gn) return 1;
  const Eigen::Vector2d n = grad / gn;
  const double s = -v / gn;
  const double flat = pixel_coverage(s, n.x(), n.y());
  const float* c = g.cells;
  const std::size_t w = g.stride;
  const double fxx = static_cast<double>(c[i + 1]) - 2.0 * c[i] + c[i - 1];
  const double fyy = static_cast<double>(c[i + w]) - 2.0 * c[i] + c[i - w];
  const double fxy = 0.25 * (static_cast<double>(c[i + w + 1]) - c[i + w - 1] - c[i - w + 1] + c[i - w - 1]);
  const double curvature =
      (fxx * grad.y() * grad.y() - 2 * fxy * grad.x() * grad.y() + fyy * grad.x() * grad.x()) / (gn * gn * gn);
  const auto [a, b] = chord(s, n);
  return std::clamp(flat - curvature * (b * b * b - a * a * a) / 6, 0.0, 1.0);
}

// Where ray d (dd = d.d) meets sphere k, or passes closest to it (a rim pixel whose centre misses).
Vector3d surface_point(const Vector3d& d, double dd, const Vector3d& s, double r) {
  const double t0 = d.dot(s) / dd;
  const Vector3d off = t0 * d - s;
  const double off2 = off.squaredNorm();
  return off2 < r * r ? Vector3d((t0 - std::sqrt((r * r - off2) / dd)) * d)
                      : Vector3d(s + off * (r / std::sqrt(std::max(off2, 1e-300))));
}

// The light sphere k's surface at x sends to the camera, shadowed by the others of the cluster;
// `mirror` as Shader::surface.
double shaded(const PatchContext& c, std::span<const Vector3d> centres, std::size_t k, const Vector3d& x,
              double* mirror = nullptr) {
  const double albedo = c.rendering.surfaces.marble;
  const Shader& shader = *c.shader;
  if (c.rendering.light->shadows) {
    for (std::size_t j = 0; j < centres.size(); ++j) {
      if (j != k && blocks(x, shader.position(), centres[j], c.radius)) {
        if (mirror) *mirror = -1;
        return albedo * shader.lit(0);
      }
    }
  }
  return shader.surface(albedo, x, (x - centres[k]) / c.radius, mirror);
}

// Where and how finely a patch's pixels are area-sampled for highlights. A highlight is close to
// a Gaussian in the normal's angle, sigma = 1 / sqrt(shininess); taken at a pixel's centre, a
// pixel spanning w of that angle loses about w^2 / (24 sigma^2) of its peak: under 2.5% for
// w < 0.75 sigma (the onboard camera's marbles, 25 px across), point sampling then. Smaller spots
// (the global camera's marbles, 9 px across) are averaged over 2 x 2 or 4 x 4 rays per pixel
// where the highlight is over half a gray level.
struct HighlightSampling {
  double near_cosine = 2;  // supersample where the mirror cosine is above this (2: never)
  int samples = 1;         // per axis
};

HighlightSampling highlight_sampling(const PatchContext& c, double spread) {
  if (!c.shader || c.shader->visible_angle() <= 0) return {};
  const double sigma = 1 / std::sqrt(c.rendering.light->shininess);
  if (spread < 0.75 * sigma) return {};
  return {std::cos(std::min(c.shader->visible_angle() + spread, 3.14159)), spread < 1.5 * sigma ? 2 : 4};
}

// Light leaving sphere k towards the camera from pixel (px, py), whose centre's ray is d: at the
// centre, or near a highlight averaged over sub-pixel rays (interpolated between pixel centres)
// that meet the sphere.
double sphere_light(const PatchContext& c, std::span<const Vector3d> centres, std::size_t k, int px, int py,
                    const Vector3d& d, double dd, const HighlightSampling& sampling) {
  if (!c.shader) return c.rendering.surfaces.marble;
  const double r = c.radius;
  const Vector3d& s = centres[k];
  const Vector3d x = surface_point(d, dd, s, r);
  double mirror = -1;
  const double at_centre = shaded(c, centres, k, x, &mirror);
  if (sampling.samples == 1 || mirror <= sampling.near_cosine) return at_centre;
  const int n = sampling.samples;
  double sum = 0;
  int hits = 0;
  for (int sy = 0; sy < n; ++sy) {
    for (int sx = 0; sx < n; ++sx) {
      const Eigen::Vector2d ray = c.rays.interpolate(px + (sx + 0.5) / n - 0.5, py + (sy + 0.5) / n - 0.5);
      const Vector3d e(ray.x(), ray.y(), 1);
      const double ee = e.squaredNorm();
      const double t0 = e.dot(s) / ee;
      if ((t0 * e - s).squaredNorm() >= r * r) continue;  // this part of the pixel sees the table
      sum += shaded(c, centres, k, surface_point(e, ee, s, r));
      ++hits;
    }
  }
  return hits > 0 ? sum / hits : at_centre;
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

// The distance grids over the rect and a pixel around it (float, in loops the compiler vectorises:
// most of a patch's pixels are only ever tested against these): each marble's outline (a sphere:
// the ray's distance from its centre less r; a disk: the table point's), and each sphere's shadow
// (the ray from the table point to the light: its distance from the centre less r, or the table
// point's own distance when the sphere is on the far side from the light, where the two meet:
// continuous).
void distance_grids(const PatchContext& c, std::span<const Vector3d> centres, const cv::Rect& rect, bool sphere,
                    bool shadows, std::vector<float>& outline, std::vector<float>& shade) {
  const std::size_t gw = static_cast<std::size_t>(rect.width) + 2;
  const std::size_t gh = static_cast<std::size_t>(rect.height) + 2;
  const std::size_t cells = gw * gh;
  const auto r = static_cast<float>(c.radius);
  const bool table_points = shadows || !sphere;
  std::vector<float> px(gw);
  std::vector<float> py(gw);
  std::vector<float> pz(gw);
  std::vector<float> hits(gw);  // 1 where the ray meets the table
  const Vector3d up = c.geometry.up;
  const auto ux = static_cast<float>(up.x());
  const auto uy = static_cast<float>(up.y());
  const auto uz = static_cast<float>(up.z());
  const auto level = static_cast<float>(c.geometry.table_level);
  const Vector3d l = c.shader ? c.shader->position() : Vector3d::Zero();
  const auto lx = static_cast<float>(l.x());
  const auto ly = static_cast<float>(l.y());
  const auto lz = static_cast<float>(l.z());
  constexpr float kNowhere = 1e3F;  // mm: the distance of a ray that meets no table
  for (std::size_t gy = 0; gy < gh; ++gy) {
    const int row = rect.y - 1 + static_cast<int>(gy);
    const float* rx = c.rays.xs(row) + rect.x - 1;
    const float* ry = c.rays.ys(row) + rect.x - 1;
    if (table_points) {
      for (std::size_t i = 0; i < gw; ++i) {
        const float along = ux * rx[i] + uy * ry[i] + uz;
        hits[i] = along < -1e-6F ? 1.0F : 0.0F;
        const float s = level / std::min(along, -1e-6F);
        px[i] = s * rx[i];
        py[i] = s * ry[i];
        pz[i] = s;
      }
    }
    for (std::size_t k = 0; k < centres.size(); ++k) {
      const auto sx = static_cast<float>(centres[k].x());
      const auto sy = static_cast<float>(centres[k].y());
      const auto sz = static_cast<float>(centres[k].z());
      float* out = &outline[k * cells + gy * gw];
      if (sphere) {
        for (std::size_t i = 0; i < gw; ++i) {
          const float x = rx[i];
          const float y = ry[i];
          const float c0 = y * sz - sy;
          const float c1 = sx - x * sz;
          const float c2 = x * sy - y * sx;
          out[i] = std::sqrt((c0 * c0 + c1 * c1 + c2 * c2) / (x * x + y * y + 1)) - r;
        }
      } else {
        for (std::size_t i = 0; i < gw; ++i) {
          const float dx = px[i] - sx;
          const float dy = py[i] - sy;
          const float dz = pz[i] - sz;
          out[i] = hits[i] > 0 ? std::sqrt(dx * dx + dy * dy + dz * dz) - r : kNowhere;
        }
      }
      if (!shadows) continue;
      float* sh = &shade[k * cells + gy * gw];
      for (std::size_t i = 0; i < gw; ++i) {
        const float ax = lx - px[i];  // towards the light
        const float ay = ly - py[i];
        const float az = lz - pz[i];
        const float wx = sx - px[i];  // towards the sphere
        const float wy = sy - py[i];
        const float wz = sz - pz[i];
        const float cx = wy * az - wz * ay;
        const float cy = wz * ax - wx * az;
        const float cz = wx * ay - wy * ax;
        const float line = std::sqrt((cx * cx + cy * cy + cz * cz) / (ax * ax + ay * ay + az * az));
        const float point = std::sqrt(wx * wx + wy * wy + wz * wz);
        const float toward = wx * ax + wy * ay + wz * az;
        sh[i] = hits[i] > 0 ? (toward > 0 ? line : point) - r : kNowhere;
      }
    }
  }
}

}  // namespace

void marble_patch(const PatchContext& c, std::span<const Vector3d> centres, const cv::Rect& rect, cv::Mat& out) {
  CV_Assert(out.type() == CV_32F && out.size() == rect.size());
  const bool sphere = c.rendering.shape == MarbleShape::sphere;
  const bool shadows = sphere && c.shader && c.rendering.light->shadows;
  const std::size_t n = centres.size();
  const std::size_t gw = static_cast<std::size_t>(rect.width) + 2;
  const std::size_t gh = static_cast<std::size_t>(rect.height) + 2;
  const std::size_t cells = gw * gh;
  std::vector<float> outline(n * cells);
  std::vector<float> shade(shadows ? n * cells : 0);
  distance_grids(c, centres, rect, sphere, shadows, outline, shade);
  std::vector<Grid> outlines;
  std::vector<Grid> shadow_grids;
  for (std::size_t k = 0; k < n; ++k) {
    outlines.push_back({&outline[k * cells], gw, far_bound(&outline[k * cells], gw, gh)});
    if (shadows) shadow_grids.push_back({&shade[k * cells], gw, far_bound(&shade[k * cells], gw, gh)});
  }

  // How far a sphere's normal turns across a pixel: the outline distance's steepest change per
  // pixel (mm) over the radius.
  double spread = 0;
  for (const Grid& g : outlines) spread = std::max(spread, g.far / (0.75 * 1.4143) / c.radius);
  const HighlightSampling sampling = highlight_sampling(c, spread);
  for (int y = 0; y < rect.height; ++y) {
    auto* row = out.ptr<float>(y);
    for (int x = 0; x < rect.width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) + 1) * gw + static_cast<std::size_t>(x) + 1;
      // Most of a patch is bare table in full light: no change.
      bool near = false;
      for (std::size_t k = 0; k < n && !near; ++k) {
        near = outlines[k].cells[i] < outlines[k].far || (shadows && shadow_grids[k].cells[i] < shadow_grids[k].far);
      }
      if (!near) {
        row[x] = 0;
        continue;
      }
      const Eigen::Vector2d ray = c.rays.at(rect.x + x, rect.y + y);
      const Vector3d d(ray.x(), ray.y(), 1);
      const double dd = d.squaredNorm();
      double covered = 0;         // of the pixel, by marbles
      std::optional<Vector3d> p;  // where the ray meets the table, when that matters
      if (!sphere) p = c.geometry.table_point(ray);
      double marble_light = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const double cover = coverage(outlines[k], i);
        if (cover <= 0) continue;
        covered += cover;
        if (sphere) {
          marble_light += cover * sphere_light(c, centres, k, rect.x + x, rect.y + y, d, dd, sampling);
        } else if (p) {
          marble_light += cover * disk_light(c, centres[k], *p, cover, gradient(outlines[k], i).norm());
        }
      }
      covered = std::min(covered, 1.0);
      const double table = c.table.at(rect.x + x, rect.y + y);
      double table_light = table;
      if (shadows && covered < 1) p = c.geometry.table_point(ray);
      if (shadows && p && covered < 1) {
        double lit = 1;  // the part of the pixel's table that sees the light
        for (std::size_t k = 0; k < n; ++k) lit *= 1 - coverage(shadow_grids[k], i);
        if (lit < 1) {
          // Only the direct light is stopped: the table keeps its ambient share.
          const Shader& s = *c.shader;
          const double direct = (1 - s.light().ambient) * s.table_direct(*p);
          table_light *= 1 - (1 - lit) * direct / (s.light().ambient + direct);
        }
      }
      row[x] = static_cast<float>(marble_light + (1 - covered) * table_light - table);
    }
  }
}

}  // namespace neopipe::sim
