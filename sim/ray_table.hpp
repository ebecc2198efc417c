#pragma once
// The ray through every pixel of a camera: its lens inverted once, since intrinsics and lens are
// fixed and only the pose changes from frame to frame. Stored as normalised undistorted
// coordinates (x, y): the ray in the camera's frame is (x, y, 1). A margin of pixels all round, so
// pixel corners, neighbours of edge pixels and light a blur brings in from beyond the image have
// their rays too.

#include <Eigen/Core>
#include <vector>

#include "sim/camera.hpp"

namespace neopipe::sim {

class RayTable {
 public:
  explicit RayTable(const Intrinsics& intrinsics, int margin = 1);

  /// The ray through the centre of pixel (x, y), -margin <= x < width + margin (y likewise).
  [[nodiscard]] Eigen::Vector2d at(int x, int y) const {
    const auto i = index(x, y);
    return {xs_[i], ys_[i]};
  }
  /// The ray through sub-pixel (u, v), interpolated bilinearly between pixel centres (clamped to
  /// the table's pixels).
  [[nodiscard]] Eigen::Vector2d interpolate(double u, double v) const;
  /// Row y's x and y coordinates, indexed by pixel x (from -margin: the pointers are to x = 0).
  [[nodiscard]] const float* xs(int y) const { return &xs_[index(0, y)]; }
  [[nodiscard]] const float* ys(int y) const { return &ys_[index(0, y)]; }
  [[nodiscard]] const Intrinsics& intrinsics() const { return k_; }
  [[nodiscard]] int margin() const { return margin_; }

 private:
  [[nodiscard]] std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y + margin_) * static_cast<std::size_t>(stride_) +
           static_cast<std::size_t>(x + margin_);
  }
  Intrinsics k_;
  int margin_;
  int stride_;
  std::vector<float> xs_;
  std::vector<float> ys_;
};

}  // namespace neopipe::sim
