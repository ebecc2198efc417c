#pragma once
// A uniform grid over the objects, so a window query costs the objects near it rather than all n:
// building every parkway and view is O(n k) for k objects per window.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace neopipe::nav::mapmaker {

class ObjectGrid {
 public:
  /// Cells of side `cell` (the window side: a window query then touches at most 2 x 2 cells). The
  /// cell grows for sparse worlds so the grid never has more than ~4 cells per object.
  ObjectGrid(std::span<const Eigen::Vector2d> objects, double cell);

  /// Appends to `out` the ids of the objects strictly inside the open box (lo, hi), ascending.
  void query(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::vector<std::uint32_t>& out) const;

  /// Calls visit(id) for every object in the cells overlapping the closed box [lo, hi], cell by
  /// cell (no order promised): a candidate set for callers that apply their own exact test.
  template <class Visit>
  void for_each_near(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, Visit&& visit) const {
    const auto [c0, r0] = cell_of(lo);
    const auto [c1, r1] = cell_of(hi);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const std::size_t k =
            static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c);
        for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i) visit(ids_[i]);
      }
    }
  }

  std::span<const Eigen::Vector2d> objects() const { return objects_; }
  double cell() const { return cell_; }
  Eigen::Vector2d lower() const { return lower_; }
  int columns() const { return cols_; }
  int rows() const { return rows_; }

 private:
  std::pair<int, int> cell_of(const Eigen::Vector2d& p) const;

  std::span<const Eigen::Vector2d> objects_;
  double cell_;
  Eigen::Vector2d lower_;
  int cols_ = 1;
  int rows_ = 1;
  std::vector<std::uint32_t> start_;  // CSR: objects of cell k are ids_[start_[k] .. start_[k+1])
  std::vector<std::uint32_t> ids_;
};

}  // namespace neopipe::nav::mapmaker
