#include "nav/mapmaker/object_grid.hpp"

#include <algorithm>
#include <cmath>

namespace neopipe::nav::mapmaker {

ObjectGrid::ObjectGrid(std::span<const Eigen::Vector2d> objects, double cell) : objects_(objects), cell_(cell) {
  Eigen::Vector2d lo(0, 0);
  Eigen::Vector2d hi(0, 0);
  if (!objects.empty()) {
    lo = hi = objects.front();
    for (const Eigen::Vector2d& p : objects) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  lower_ = lo;
  // At most ~4 cells per object: a huge world with few objects must not allocate a huge grid.
  const double cap = 4.0 * static_cast<double>(std::max<std::size_t>(objects.size(), 1));
  const Eigen::Vector2d extent = hi - lo;
  while ((std::floor(extent.x() / cell_) + 1) * (std::floor(extent.y() / cell_) + 1) > cap) cell_ *= 2;
  cols_ = static_cast<int>(std::floor(extent.x() / cell_)) + 1;
  rows_ = static_cast<int>(std::floor(extent.y() / cell_)) + 1;
  const std::size_t cells = static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_);
  std::vector<std::uint32_t> cell_of_object(objects.size());
  start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto [c, r] = cell_of(objects[i]);
    cell_of_object[i] = static_cast<std::uint32_t>(r * cols_ + c);
    ++start_[cell_of_object[i] + 1];
  }
  for (std::size_t k = 0; k < cells; ++k) start_[k + 1] += start_[k];
  ids_.resize(objects.size());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < objects.size(); ++i) ids_[fill[cell_of_object[i]]++] = static_cast<std::uint32_t>(i);
}

std::pair<int, int> ObjectGrid::cell_of(const Eigen::Vector2d& p) const {
  const auto clamp = [](double v, int n) {
    if (!(v >= 0)) return 0;  // also NaN
    return v >= n - 1 ? n - 1 : static_cast<int>(v);
  };
  return {clamp(std::floor((p.x() - lower_.x()) / cell_), cols_),
          clamp(std::floor((p.y() - lower_.y()) / cell_), rows_)};
}

void ObjectGrid::query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::vector<std::uint32_t>& out) const {
  const std::size_t first = out.size();
  for_each_near(lo, hi, [&](std::uint32_t id) {
    const Eigen::Vector2d& p = objects_[id];
    if (p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y()) out.push_back(id);
  });
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

}  // namespace neopipe::nav::mapmaker
