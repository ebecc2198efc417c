#pragma once
// The ink shared by neopipe's charts (map statistics, reliability diagrams), BGR as OpenCV draws.

#include <opencv2/core/types.hpp>

namespace neopipe::apps {

inline const cv::Scalar kChartInk(0, 0, 0);         ///< axes, ticks, text
inline const cv::Scalar kChartGrid(200, 200, 200);  ///< grid lines, reference diagonals

}  // namespace neopipe::apps
