#pragma once
// The bare table's light in one frame, per pixel (gray levels, before vignetting and the sensor):
// albedo x texture x (ambient + direct light). Exact at nodes every `spacing` pixels and bilinear
// between them: the light changes slowly over the table, and the texture's finest features span
// two nodes or more (SceneRenderer picks the spacing), so a frame costs a few thousand texture
// look-ups instead of one per pixel. Shadows are the marbles' patches' business.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "sim/frame_geometry.hpp"
#include "sim/ray_table.hpp"
#include "sim/rendering.hpp"
#include "sim/table_texture.hpp"

namespace neopipe::sim {

class TableField {
 public:
  /// Nodes cover pixels -margin .. size + margin - 1 each way; `rays` must reach margin + spacing
  /// beyond the image.
  TableField(const Rendering& rendering, const TableTexture& texture, const FrameGeometry& geometry,
             const RayTable& rays, int spacing, int margin);

  /// At pixel (x, y), -margin <= x < width + margin (and y likewise).
  [[nodiscard]] float at(int x, int y) const {
    const int px = x + margin_;
    const int py = y + margin_;
    const int i = px / spacing_;
    const int j = py / spacing_;
    const float fx = static_cast<float>(px - i * spacing_) * inverse_;
    const float fy = static_cast<float>(py - j * spacing_) * inverse_;
    const float* a =
        &nodes_[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(i)];
    const float* b = a + columns_;
    const float top = a[0] + fx * (a[1] - a[0]);
    const float bottom = b[0] + fx * (b[1] - b[0]);
    return top + fy * (bottom - top);
  }
  /// The whole image (CV_32F, the camera's size).
  [[nodiscard]] cv::Mat image() const;
  [[nodiscard]] int margin() const { return margin_; }

 private:
  cv::Size size_;
  int spacing_;
  int margin_;
  float inverse_;
  int columns_;
  std::vector<float> nodes_;  // row-major, columns_ per node row
};

}  // namespace neopipe::sim
