#pragma once
// The bare table's light in one frame, per pixel (gray levels, before vignetting and the sensor):
// albedo x texture x (ambient + direct light). Exact at nodes every `spacing` pixels and bilinear
// between them: the light changes slowly over the table, and the texture's finest features span
// a node and a half or more (SceneRenderer picks the spacing), so a frame costs a few thousand
// texture look-ups instead of one per pixel. Shadows are the marbles' patches' business.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "sim/frame_geometry.hpp"
#include "sim/ray_table.hpp"
#include "sim/rendering.hpp"
#include "sim/table_texture.hpp"

namespace neopipe::sim {

class TableField {
 public:
  /// Nodes cover pixels -margin .. size + margin - 1 each way; `spacing` is 1, 2, 4, 8 or 16 and
  /// divides `margin`; `rays` must reach margin + spacing beyond the image.
  TableField(const Rendering& rendering, const TableTexture& texture, const FrameGeometry& geometry,
             const RayTable& rays, int spacing, int margin);

  /// At pixel (x, y), -margin <= x < width + margin (and y likewise).
  [[nodiscard]] float at(int x, int y) const {
    const int px = x + margin_;
    const int py = y + margin_;
    const int i = px >> shift_;
    const int j = py >> shift_;
    const float fx = static_cast<float>(px - (i << shift_)) * inverse_;
    const float fy = static_cast<float>(py - (j << shift_)) * inverse_;
    const float* a = &nodes_[static_cast<std::size_t>(j) * columns_ + static_cast<std::size_t>(i)];
    const float* b = a + columns_;
    const float left = a[0] + fy * (b[0] - a[0]);
    const float right = a[1] + fy * (b[1] - a[1]);
    return left + fx * (right - left);
  }
  /// The whole image (CV_32F, the camera's size).
  [[nodiscard]] cv::Mat image() const;
  [[nodiscard]] int margin() const { return margin_; }

 private:
  cv::Size size_;
  int spacing_;
  int shift_;  // log2(spacing)
  int margin_;
  float inverse_;
  std::size_t columns_;
  std::vector<float> nodes_;  // row-major, columns_ per node row
};

}  // namespace neopipe::sim
