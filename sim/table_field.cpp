#include "sim/table_field.hpp"

#include "sim/shading.hpp"

namespace neopipe::sim {

TableField::TableField(const Rendering& rendering, const TableTexture& texture, const FrameGeometry& geometry,
                       const RayTable& rays, int spacing, int margin)
    : size_(rays.intrinsics().size), spacing_(spacing), margin_(margin), inverse_(1.0F / static_cast<float>(spacing)) {
  // Node i sits at pixel -margin + i spacing; one more node than the span needs, so at() may read
  // the node after the one it is in.
  columns_ = (size_.width + 2 * margin - 1) / spacing + 2;
  const int rows = (size_.height + 2 * margin - 1) / spacing + 2;
  nodes_.resize(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows));
  const Surfaces& s = rendering.surfaces;
  std::optional<Shader> shader;
  if (rendering.light && geometry.light) shader.emplace(*rendering.light, *geometry.light, geometry.light_height);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns_; ++i) {
      const auto p = geometry.table_point(rays.at(-margin + i * spacing, -margin + j * spacing));
      double value = 0;  // looking past the table's horizon
      if (p) {
        value = s.table;
        if (s.texture > 0) {
          const Eigen::Vector3d w = geometry.to_world(*p);
          value *= 1 + s.texture * texture(w.x(), w.y());
        }
        if (shader) value *= shader->lit(shader->table_direct(*p));
      }
      nodes_[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(i)] =
          static_cast<float>(value);
    }
  }
}

cv::Mat TableField::image() const {
  cv::Mat out(size_, CV_32F);
  const int w = size_.width;
  std::vector<float> line(static_cast<std::size_t>(columns_));  // node row interpolated to the pixel row
  for (int y = 0; y < size_.height; ++y) {
    const int py = y + margin_;
    const int j = py / spacing_;
    const float fy = static_cast<float>(py - j * spacing_) * inverse_;
    const float* a = &nodes_[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_)];
    const float* b = a + columns_;
    for (int i = 0; i < columns_; ++i) line[static_cast<std::size_t>(i)] = a[i] + fy * (b[i] - a[i]);
    auto* o = out.ptr<float>(y);
    // Pixel x is node (x + margin) / spacing plus a fraction: straight segments between nodes.
    for (int x = 0; x < w;) {
      const int px = x + margin_;
      const int i = px / spacing_;
      const int k0 = px - i * spacing_;
      const float base = line[static_cast<std::size_t>(i)];
      const float slope = (line[static_cast<std::size_t>(i) + 1] - base) * inverse_;
      const int n = std::min(spacing_ - k0, w - x);
      for (int k = 0; k < n; ++k) o[x + k] = base + slope * static_cast<float>(k0 + k);
      x += n;
    }
  }
  return out;
}

}  // namespace neopipe::sim
