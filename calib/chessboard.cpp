#include "calib/chessboard.hpp"

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/grid_labelling.hpp"

namespace neopipe::calib {

std::optional<std::vector<Eigen::Vector2d>> find_chessboard(const cv::Mat& image, int cols, int rows) {
  cv::Mat gray = image;
  if (image.channels() == 3) cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(gray, {cols, rows}, corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return std::nullopt;
  }
  // The refinement window: a quarter of the smallest corner spacing, so it never reaches the next
  // corner, within OpenCV's usual 3..11.
  double spacing = 1e9;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i + 1 < cols; ++i) {
      const auto d = corners[grid_index(i + 1, j, cols)] - corners[grid_index(i, j, cols)];
      spacing = std::min(spacing, std::hypot(static_cast<double>(d.x), static_cast<double>(d.y)));
    }
  }
  const int win = std::clamp(static_cast<int>(spacing / 4), 3, 11);
  cv::cornerSubPix(gray, corners, {win, win}, {-1, -1},
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  std::vector<Eigen::Vector2d> points;
  points.reserve(corners.size());
  for (const auto& c : corners) points.emplace_back(c.x, c.y);
  return upright_labelling(points, cols, rows);
}

}  // namespace neopipe::calib
