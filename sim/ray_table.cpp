#include "sim/ray_table.hpp"

#include <algorithm>
#include <cmath>

namespace neopipe::sim {

RayTable::RayTable(const Intrinsics& k, int margin) : k_(k), margin_(margin), stride_(k.size.width + 2 * margin) {
  const std::size_t cells = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(k.size.height + 2 * margin);
  xs_.resize(cells);
  ys_.resize(cells);
  const Lens lens = k.lens();
  const bool distorted = lens != Lens{};
  Eigen::Vector2d row_start(0, 0);
  for (int y = -margin; y < k.size.height + margin; ++y) {
    // Newton from the answer extrapolated from the two pixels before: one or two steps per pixel
    // instead of a dozen.
    Eigen::Vector2d before = row_start;
    Eigen::Vector2d last = row_start;
    for (int x = -margin; x < k.size.width + margin; ++x) {
      const Eigen::Vector2d d((x - k.cx) / k.fx, (y - k.cy) / k.fy);
      Eigen::Vector2d guess = x == -margin ? row_start : (x == -margin + 1 ? last : Eigen::Vector2d(2 * last - before));
      if (x == -margin && y == -margin) guess = d;
      // To 1e-12 of the focal length: far below what float storage keeps.
      const Eigen::Vector2d n = distorted ? undistort(lens, d, guess, 1e-12) : d;
      if (x == -margin) row_start = n;
      before = last;
      last = n;
      const auto i = index(x, y);
      xs_[i] = static_cast<float>(n.x());
      ys_[i] = static_cast<float>(n.y());
    }
  }
}

Eigen::Vector2d RayTable::interpolate(double u, double v) const {
  const double cu = std::clamp(u, static_cast<double>(-margin_), static_cast<double>(k_.size.width + margin_ - 1));
  const double cv = std::clamp(v, static_cast<double>(-margin_), static_cast<double>(k_.size.height + margin_ - 1));
  const int x0 = std::min(static_cast<int>(std::floor(cu)), k_.size.width + margin_ - 2);
  const int y0 = std::min(static_cast<int>(std::floor(cv)), k_.size.height + margin_ - 2);
  const double fx = cu - x0;
  const double fy = cv - y0;
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

}  // namespace neopipe::sim
