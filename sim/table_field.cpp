#include "sim/table_field.hpp"

#include <bit>
#include <stdexcept>

namespace neopipe::sim {
namespace {

// Row `y` of the image from its interpolated node row `line`: straight segments of S pixels
// between nodes, a fixed-width loop the compiler turns into vector operations.
template <int S>
void expand(const float* line, int margin, int width, float* out) {
  constexpr float kInverse = 1.0F / S;
  const int first = margin / S;  // margin is a multiple of S: pixel 0 sits on node `first`
  int x = 0;
  for (int i = first; x + S <= width; ++i, x += S) {
    const float base = line[i];
    const float slope = (line[i + 1] - base) * kInverse;
    for (int k = 0; k < S; ++k) out[x + k] = base + slope * static_cast<float>(k);
  }
  for (int k = 0; x < width; ++x, ++k) {
    const int i = first + width / S;
    out[x] = line[i] + (line[i + 1] - line[i]) * kInverse * static_cast<float>(k);
  }
}

}  // namespace

TableField::TableField(const Rendering& rendering, const TableTexture& texture, const FrameGeometry& geometry,
                       const RayTable& rays, int spacing, int margin)
    : size_(rays.intrinsics().size),
      spacing_(spacing),
      shift_(std::countr_zero(static_cast<unsigned>(spacing))),
      margin_(margin),
      inverse_(1.0F / static_cast<float>(spacing)) {
  if (!std::has_single_bit(static_cast<unsigned>(spacing)) || spacing > 16 || margin % spacing != 0) {
    throw std::invalid_argument("table field: spacing must be 1, 2, 4, 8 or 16 and divide the margin");
  }
  // Node i sits at pixel -margin + i spacing; one more node than the span needs, so at() may read
  // the node after the one it is in.
  columns_ = static_cast<std::size_t>((size_.width + 2 * margin - 1) / spacing) + 2;
  const int rows = (size_.height + 2 * margin - 1) / spacing + 2;
  nodes_.resize(columns_ * static_cast<std::size_t>(rows));

  // Every node of a row at once, in float: the ray meets the table (camera frame), that point in
  // world coordinates gives the texture, its distance from the light the direct light.
  const Surfaces& s = rendering.surfaces;
  const auto n = static_cast<int>(columns_);
  std::vector<float> rx(columns_);
  std::vector<float> ry(columns_);
  std::vector<float> wx(columns_);
  std::vector<float> wy(columns_);
  std::vector<float> tex(columns_);
  const auto f = [](double v) { return static_cast<float>(v); };
  const Eigen::Matrix3d rt = geometry.rotation.transpose();
  const Eigen::Vector3d& t = geometry.translation;
  const float ux = f(geometry.up.x());
  const float uy = f(geometry.up.y());
  const float uz = f(geometry.up.z());
  const float level = f(geometry.table_level);
  const bool lit = rendering.light && geometry.light;
  const Eigen::Vector3d l = lit ? *geometry.light : Eigen::Vector3d::Zero();
  const float h2 = f(geometry.light_height * geometry.light_height);
  const float ambient = lit ? f(rendering.light->ambient) : 1.0F;
  const float table = f(s.table);
  const float contrast = f(s.texture);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d ray = rays.at(-margin + i * spacing, -margin + j * spacing);
      rx[static_cast<std::size_t>(i)] = f(ray.x());
      ry[static_cast<std::size_t>(i)] = f(ray.y());
    }
    float* out = &nodes_[static_cast<std::size_t>(j) * columns_];
    for (int i = 0; i < n; ++i) {
      const float x = rx[static_cast<std::size_t>(i)];
      const float y = ry[static_cast<std::size_t>(i)];
      const float along = ux * x + uy * y + uz;
      const float d = level / std::min(along, -1e-6F);  // depth along the ray to the table
      const float px = d * x - f(t.x());
      const float py = d * y - f(t.y());
      const float pz = d - f(t.z());
      wx[static_cast<std::size_t>(i)] = f(rt(0, 0)) * px + f(rt(0, 1)) * py + f(rt(0, 2)) * pz;
      wy[static_cast<std::size_t>(i)] = f(rt(1, 0)) * px + f(rt(1, 1)) * py + f(rt(1, 2)) * pz;
      float light = 1;
      if (lit) {
        const float dx = f(l.x()) - d * x;
        const float dy = f(l.y()) - d * y;
        const float dz = f(l.z()) - d;
        const float q2 = h2 / (dx * dx + dy * dy + dz * dz);
        light = ambient + (1 - ambient) * q2 * std::sqrt(q2);  // (height / distance)^3
      }
      out[i] = along < -1e-6F ? table * light : 0.0F;  // 0: looking past the table's horizon
    }
    if (contrast > 0) {
      texture.evaluate(wx.data(), wy.data(), tex.data(), n);
      for (int i = 0; i < n; ++i) out[i] *= 1 + contrast * tex[static_cast<std::size_t>(i)];
    }
  }
}

cv::Mat TableField::image() const {
  cv::Mat out(size_, CV_32F);
  std::vector<float> line(columns_);  // node row interpolated to the pixel row
  for (int y = 0; y < size_.height; ++y) {
    const int py = y + margin_;
    const int j = py >> shift_;
    const float fy = static_cast<float>(py - (j << shift_)) * inverse_;
    const float* a = &nodes_[static_cast<std::size_t>(j) * columns_];
    const float* b = a + columns_;
    for (std::size_t i = 0; i < columns_; ++i) line[i] = a[i] + fy * (b[i] - a[i]);
    auto* o = out.ptr<float>(y);
    switch (spacing_) {
      case 1:
        std::copy_n(line.data() + margin_, size_.width, o);
        break;
      case 2:
        expand<2>(line.data(), margin_, size_.width, o);
        break;
      case 4:
        expand<4>(line.data(), margin_, size_.width, o);
        break;
      case 8:
        expand<8>(line.data(), margin_, size_.width, o);
        break;
      default:
        expand<16>(line.data(), margin_, size_.width, o);
        break;
    }
  }
  return out;
}

}  // namespace neopipe::sim
