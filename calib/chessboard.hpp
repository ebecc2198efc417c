#pragma once
// Chessboard targets: OpenCV's corner detection and sub-pixel refinement, the corners then labelled
// by the same rule as dot grids (a rotation seen upright, never a mirror), so a board lying on the
// workspace maps the right way round.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

namespace neopipe::calib {

/// The cols x rows inner corners (index j * cols + i), or nothing if the board is not found.
std::optional<std::vector<Eigen::Vector2d>> find_chessboard(const cv::Mat& image, int cols, int rows);

}  // namespace neopipe::calib
