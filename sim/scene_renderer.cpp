#include "sim/scene_renderer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <vector>

#include "sim/frame_geometry.hpp"
#include "sim/marble_patch.hpp"
#include "sim/shading.hpp"

namespace neopipe::sim {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

const Rendering& validated(const Rendering& r) {
  r.validate();
  return r;
}

// Pixels between the table's exact nodes: a power of two at most a third of the texture's finest
// features (half its coarse scale) at the image centre's scale, at most 8, so bilinear steps
// between nodes stay within a tenth of the texture's amplitude (tested); with no texture the light
// alone, which changes over hundreds of pixels: 16.
int node_spacing(const Rendering& r, const PinholeCamera& camera) {
  if (r.surfaces.texture <= 0) return 16;
  const cv::Size s = camera.size();
  const auto p = camera.plane_point({(s.width - 1) / 2.0, (s.height - 1) / 2.0});
  if (!p) return 1;
  const double px_per_mm = std::sqrt(std::abs(camera.plane_jacobian(*p).determinant()));
  const double finest_px = r.surfaces.texture_scale / 2 * px_per_mm;
  int spacing = 1;
  while (spacing < 8 && 2 * spacing <= finest_px / 3) spacing *= 2;
  return spacing;
}

// Pixels beyond the image whose light the widest blur brings into it, one more for the outlines'
// differences, rounded up to whole node spacings.
int blur_margin(const Defocus& d, int spacing) {
  const int m = static_cast<int>(std::ceil(4 * std::max(d.centre, d.corner))) + 2;
  return (m + spacing - 1) / spacing * spacing;
}

// The box of image pixels (inclusive bounds as a Rect) holding these points' projections, or an
// empty Rect if any is behind the camera.
cv::Rect image_box(const PinholeCamera& camera, std::span<const Vector3d> points) {
  double x0 = 1e30;
  double y0 = 1e30;
  double x1 = -1e30;
  double y1 = -1e30;
  for (const auto& p : points) {
    const auto px = camera.project(p);
    if (!px) return {};
    x0 = std::min(x0, px->x());
    y0 = std::min(y0, px->y());
    x1 = std::max(x1, px->x());
    y1 = std::max(y1, px->y());
  }
  // Two pixels for the lens bending the straight edges these corners span, and rounding.
  const int ix0 = static_cast<int>(std::floor(x0)) - 2;
  const int iy0 = static_cast<int>(std::floor(y0)) - 2;
  return {ix0, iy0, static_cast<int>(std::ceil(x1)) + 2 - ix0 + 1, static_cast<int>(std::ceil(y1)) + 2 - iy0 + 1};
}

// Where a marble and its shadow can change the image: the projections of the box around the
// sphere (or the disk's square), and of the box on the table around the shadow of that box.
cv::Rect support(const Rendering& r, const PinholeCamera& camera, const Vector2d& c, double radius) {
  const bool sphere = r.shape == MarbleShape::sphere;
  const double z = sphere ? radius : 0.0;
  std::vector<Vector3d> corners;
  for (const double dx : {-radius, radius}) {
    for (const double dy : {-radius, radius}) {
      if (sphere) {
        corners.emplace_back(c.x() + dx, c.y() + dy, z - radius);
        corners.emplace_back(c.x() + dx, c.y() + dy, z + radius);
      } else {
        corners.emplace_back(c.x() + dx, c.y() + dy, 0);
      }
    }
  }
  cv::Rect box = image_box(camera, corners);
  if (sphere && r.light && r.light->shadows && !box.empty()) {
    const Vector3d& l = r.light->position;
    Eigen::AlignedBox2d shadow;
    for (const auto& q : corners) shadow.extend(Vector2d((l + (q - l) * l.z() / (l.z() - q.z())).head<2>()));
    std::vector<Vector3d> table;
    for (const double x : {shadow.min().x(), shadow.max().x()}) {
      for (const double y : {shadow.min().y(), shadow.max().y()}) table.emplace_back(x, y, 0);
    }
    const cv::Rect s = image_box(camera, table);
    if (!s.empty()) box |= s;
  }
  return box;
}

// Groups of marbles whose supports overlap (union-find), each with the union of their supports.
struct Cluster {
  std::vector<std::size_t> members;
  cv::Rect box;
};

std::vector<Cluster> clusters(const std::vector<cv::Rect>& boxes) {
  std::vector<std::size_t> parent(boxes.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      if ((boxes[i] & boxes[j]).area() > 0) parent[root(i)] = root(j);
    }
  }
  std::vector<Cluster> out;
  std::vector<long> slot(boxes.size(), -1);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::size_t k = root(i);
    if (slot[k] < 0) {
      slot[k] = static_cast<long>(out.size());
      out.push_back({{}, boxes[i]});
    }
    Cluster& c = out[static_cast<std::size_t>(slot[k])];
    c.members.push_back(i);
    c.box |= boxes[i];
  }
  return out;
}

}  // namespace

SceneRenderer::SceneRenderer(const Rendering& rendering, const PinholeCamera& camera)
    : rendering_(validated(rendering)),
      intrinsics_(camera.intrinsics()),
      spacing_(node_spacing(rendering, camera)),
      margin_(blur_margin(rendering.defocus, spacing_)),
      rays_(camera.intrinsics(), margin_ + spacing_ + 1),
      texture_(rendering.surfaces.texture_scale, rendering.surfaces.texture_seed),
      defocus_(rendering.defocus, camera.size()),
      sensor_(rendering.sensor, camera.size()),
      cached_rotation_(camera.rotation()),
      cached_translation_(camera.translation()) {
  if (rendering.is_image_model()) today_.emplace(rendering.image_model(), camera.size());
  cached_table_.emplace(table(camera));
}

void SceneRenderer::check_camera(const PinholeCamera& camera) const {
  if (!(camera.intrinsics() == intrinsics_)) {
    throw std::invalid_argument("scene renderer: the camera's intrinsics or lens differ from the renderer's");
  }
}

TableField SceneRenderer::table(const PinholeCamera& camera) const {
  if (cached_table_ && camera.rotation() == cached_rotation_ && camera.translation() == cached_translation_) {
    return *cached_table_;
  }
  const FrameGeometry geometry(camera, rendering_.light);
  return {rendering_, texture_, geometry, rays_, spacing_, margin_};
}

cv::Mat SceneRenderer::field_radiance(std::span<const Vector2d> centres, double diameter,
                                      const PinholeCamera& camera) const {
  const double radius = diameter / 2;
  const bool sphere = rendering_.shape == MarbleShape::sphere;
  const FrameGeometry geometry(camera, rendering_.light);
  if (sphere && rendering_.light && !(rendering_.light->position.z() > diameter)) {
    throw std::invalid_argument("light.position: z = " + std::to_string(rendering_.light->position.z()) +
                                " mm is not above the marbles' tops (" + std::to_string(diameter) + " mm)");
  }
  const TableField table_light = table(camera);
  cv::Mat light = table_light.image();

  // The part of the table whose marbles or shadows can reach the image (or its margin): the table
  // points of the margin's corners and edge midpoints, grown by a marble, its shadow's reach and a
  // quarter for the lens (the reach: a ball's top 2r up throws its shadow 2r x horizontal distance
  // / (light height - 2r) away).
  const cv::Size s = camera.size();
  Eigen::AlignedBox2d seen;
  bool horizon = false;
  for (const int u : {-margin_, (s.width - 1) / 2, s.width - 1 + margin_}) {
    for (const int v : {-margin_, (s.height - 1) / 2, s.height - 1 + margin_}) {
      const auto p = geometry.table_point(rays_.at(u, v));
      if (!p) {
        horizon = true;
        continue;
      }
      seen.extend(Vector2d(geometry.to_world(*p).head<2>()));
    }
  }
  double grow = diameter;
  if (sphere && rendering_.light && rendering_.light->shadows && !horizon) {
    const Vector3d& l = rendering_.light->position;
    double far = 0;
    for (int i = 0; i < 4; ++i) {
      far = std::max(far, (seen.corner(static_cast<Eigen::AlignedBox2d::CornerType>(i)) - l.head<2>()).norm());
    }
    grow += diameter * far / (l.z() - diameter);
  }
  const Eigen::AlignedBox2d reach(seen.min() - seen.sizes() / 4 - Vector2d::Constant(grow),
                                  seen.max() + seen.sizes() / 4 + Vector2d::Constant(grow));

  const cv::Rect area(-margin_ + 1, -margin_ + 1, s.width + 2 * margin_ - 2, s.height + 2 * margin_ - 2);
  std::vector<std::size_t> ids;
  std::vector<cv::Rect> boxes;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (!horizon && !reach.contains(centres[i])) continue;
    const cv::Rect box = support(rendering_, camera, centres[i], radius) & area;
    if (box.empty()) continue;
    ids.push_back(i);
    boxes.push_back(box);
  }

  std::optional<Shader> shader;
  if (rendering_.light) shader.emplace(*rendering_.light, *geometry.light, geometry.light_height);
  const PatchContext context{rendering_, geometry, rays_, table_light, shader, radius};
  const int reach_px = defocus_.reach();
  const cv::Rect image({0, 0}, s);
  std::vector<Vector3d> members;
  for (const Cluster& c : clusters(boxes)) {
    members.clear();
    for (const std::size_t m : c.members) {
      const Vector2d& p = centres[ids[m]];
      members.push_back(geometry.to_camera({p.x(), p.y(), sphere ? radius : 0.0}));
    }
    // The blur spreads the patch by its reach: zeros that far around it (within the rays' margin).
    const cv::Rect rect =
        cv::Rect(c.box.x - reach_px, c.box.y - reach_px, c.box.width + 2 * reach_px, c.box.height + 2 * reach_px) &
        area;
    if ((rect & image).empty()) continue;
    cv::Mat patch = cv::Mat::zeros(rect.size(), CV_32F);
    cv::Mat marbles = patch(c.box - rect.tl());
    marble_patch(context, members, c.box, marbles);
    defocus_.blur_patch(patch, c.box.x + c.box.width / 2.0, c.box.y + c.box.height / 2.0);
    const cv::Rect inside = rect & image;
    light(inside) += patch(inside - rect.tl());
  }
  return light;
}

cv::Mat SceneRenderer::radiance(std::span<const Vector2d> centres, double diameter, const PinholeCamera& camera) const {
  check_camera(camera);
  return field_radiance(centres, diameter, camera);
}

cv::Mat SceneRenderer::render(std::span<const Vector2d> centres, double diameter, const PinholeCamera& camera,
                              std::int64_t frame) const {
  return render(centres, camera, centres, camera, diameter, frame);
}

cv::Mat SceneRenderer::render(std::span<const Vector2d> even_centres, const PinholeCamera& even_camera,
                              std::span<const Vector2d> odd_centres, const PinholeCamera& odd_camera, double diameter,
                              std::int64_t frame) const {
  check_camera(even_camera);
  check_camera(odd_camera);
  if (today_) return today_->render(even_centres, diameter, even_camera, frame);
  const cv::Mat even = field_radiance(even_centres, diameter, even_camera);
  if (!rendering_.interlace) return sensor_.expose(even, even, frame);
  const cv::Mat odd = field_radiance(odd_centres, diameter, odd_camera);
  return sensor_.expose(even, odd, frame);
}

cv::Mat SceneRenderer::expose(const cv::Mat& light, std::int64_t frame) const {
  if (today_) return today_->expose(light, frame);
  if (light.size() != size() || light.type() != CV_32F) {
    throw std::invalid_argument("scene renderer: light image of the wrong size or type");
  }
  const cv::Mat blurred = defocus_.blur_frame(light);
  return sensor_.expose(blurred, blurred, frame);
}

}  // namespace neopipe::sim
