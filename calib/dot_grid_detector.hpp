#pragma once
// Finding a dot-grid target in an image: the engine's blob graph extracts the dots' centroids,
// order_dot_grid puts them in grid order.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

namespace neopipe::calib {

/// The `cols` x `rows` dot centres (px, (0,0) the top-left pixel's centre) of a dot grid in `image`
/// (CV_8UC1 gray or CV_8UC3 BGR), in order_dot_grid's order. Bright dots on a dark board are tried
/// first, then dark dots on a light board. Nothing if no whole grid is seen (no target, some dots
/// cut off by the image border, or strays that cannot be told from dots). Throws
/// std::invalid_argument for an image of another type.
std::optional<std::vector<Eigen::Vector2d>> find_dot_grid(const cv::Mat& image, int cols, int rows);

}  // namespace neopipe::calib
