#pragma once
// Histogram of an 8-bit image: PIPE's iconic-to-symbolic reduction of a frame to 256 counts.

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/types.hpp"

namespace neopipe::kernels {

using Histogram = std::array<std::uint64_t, 256>;
inline constexpr Footprint histogram_footprint = Footprint::frame;

/// Adds the counts of `rows` of src (CV_8UC1) to hist. Stripes can be counted separately and
/// summed: counts are integers, so the result does not depend on how the frame was cut.
void accumulate_histogram(const cv::Mat& src, Histogram& hist, cv::Range rows = cv::Range::all());

Histogram histogram(const cv::Mat& src);

}  // namespace neopipe::kernels
