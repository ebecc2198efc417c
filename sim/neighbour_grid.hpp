#pragma once
// A uniform grid over the workspace for "is any marble closer than d?" in constant time, so
// placing or checking n marbles costs O(n), not O(n^2).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace neopipe::sim {

class NeighbourGrid {
 public:
  /// `cell` must be at least the largest distance any_within will be asked about.
  NeighbourGrid(const Eigen::Vector2d& size, double cell)
      : cell_(std::max({cell, 1e-9, size.x() / kMaxCellsPerSide, size.y() / kMaxCellsPerSide})),
        cols_(std::max(1, static_cast<int>(std::ceil(size.x() / cell_)))),
        rows_(std::max(1, static_cast<int>(std::ceil(size.y() / cell_)))),
        cells_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_)) {}

  void insert(const Eigen::Vector2d& p, std::size_t id) { cells_[index(col(p.x()), row(p.y()))].push_back({p, id}); }

  /// Calls f(id) for every inserted point strictly closer than d to p (d <= cell), as inserted.
  /// Positions are those at insertion.
  template <class F>
  void for_each_within(const Eigen::Vector2d& p, double d, F&& f) const {
    const int c0 = col(p.x());
    const int r0 = row(p.y());
    for (int r = std::max(0, r0 - 1); r <= std::min(rows_ - 1, r0 + 1); ++r) {
      for (int c = std::max(0, c0 - 1); c <= std::min(cols_ - 1, c0 + 1); ++c) {
        for (const auto& e : cells_[index(c, r)]) {
          if ((e.p - p).squaredNorm() < d * d) f(e.id);
        }
      }
    }
  }

  /// Some inserted point strictly closer than d to p (d <= cell), if any.
  [[nodiscard]] std::optional<std::size_t> any_within(const Eigen::Vector2d& p, double d) const {
    const int c0 = col(p.x());
    const int r0 = row(p.y());
    for (int r = std::max(0, r0 - 1); r <= std::min(rows_ - 1, r0 + 1); ++r) {
      for (int c = std::max(0, c0 - 1); c <= std::min(cols_ - 1, c0 + 1); ++c) {
        for (const auto& e : cells_[index(c, r)]) {
          if ((e.p - p).squaredNorm() < d * d) return e.id;
        }
      }
    }
    return std::nullopt;
  }

 private:
  // Cells are made larger than asked when the workspace is over this many cells a side: a world file
  // may give any finite size, and [2e59, 100] mm with 5 mm marbles asked for a cell count beyond
  // int (undefined behaviour) and beyond memory (found by fuzz/fuzz_world.cpp). Larger cells stay
  // correct (a cell need only be at least the query distance); the grid is at most 24 MiB.
  static constexpr double kMaxCellsPerSide = 1024;

  struct Entry {
    Eigen::Vector2d p;
    std::size_t id;
  };
  [[nodiscard]] int col(double x) const { return std::clamp(static_cast<int>(std::floor(x / cell_)), 0, cols_ - 1); }
  [[nodiscard]] int row(double y) const { return std::clamp(static_cast<int>(std::floor(y / cell_)), 0, rows_ - 1); }
  [[nodiscard]] std::size_t index(int c, int r) const {
    return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c);
  }

  double cell_;
  int cols_;
  int rows_;
  std::vector<std::vector<Entry>> cells_;
};

}  // namespace neopipe::sim
