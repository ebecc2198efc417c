#pragma once
// The labelling rule every grid target follows (dot grids, chessboards): a rotation of the grid,
// never its mirror image, seen upright. See order_dot_grid for the rule in full.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace neopipe::calib {

/// Index of column i, row j in a grid stored row by row.
inline std::size_t grid_index(int i, int j, int cols) {
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(i);
}

/// Relabels `points` (cols x rows, index j * cols + i, in any consistent grid order, mirrored or
/// not) so that cross(col_dir, row_dir) < 0 in pixel coordinates and, among the rotations the
/// grid's shape allows, the column axis points most nearly along +u.
std::vector<Eigen::Vector2d> upright_labelling(const std::vector<Eigen::Vector2d>& points, int cols, int rows);

}  // namespace neopipe::calib
