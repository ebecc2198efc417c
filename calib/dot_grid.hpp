#pragma once
// Ordering detected dot centroids into the rows and columns of a dot-grid target, as OpenCV's
// findCirclesGrid does, robust to the grid's rotation and perspective and to a few stray blobs.

#include <Eigen/Core>
#include <opencv2/core/types.hpp>
#include <optional>
#include <vector>

namespace neopipe::calib {

/// A dot found in the image: its centroid and its area (stray blobs differ in area from the dots).
struct Dot {
  Eigen::Vector2d centre;  ///< px
  double area = 0;         ///< px^2
};

/// `cols` x `rows` dot centres in grid order: index j * cols + i is the dot in column i of row j.
/// The labelling is a rotation of the grid, never its mirror image: seen in the image, the row axis
/// (j growing) is 90 degrees counter-clockwise from the column axis (i growing) on a screen with v
/// up, i.e. cross(col_dir, row_dir) < 0 in (u, v) pixel coordinates, as a target lying face up
/// under a camera with North up (i East, j North) appears. Of the rotations the grid's shape allows
/// (two for cols != rows, four for a square grid) it is the one whose column axis points most
/// nearly along +u. Nothing if the dots do not form such a grid (too few, strays that cannot be told
/// from dots, not one-to-one, or the handedness cannot hold).
std::optional<std::vector<Eigen::Vector2d>> order_dot_grid(const std::vector<Dot>& dots, int cols, int rows);

}  // namespace neopipe::calib
