#pragma once
// Threshold: out = (in > T) ? high : 0, OpenCV's THRESH_BINARY; and Otsu's choice of T.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/histogram.hpp"
#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint threshold_footprint = Footprint::point;

void threshold_row(const std::uint8_t* in, std::uint8_t* out, int width, std::uint8_t t, std::uint8_t high) noexcept;

/// dst = (src > t) ? high : 0 on `rows`. t may be -1 (everything passes) to 255 (nothing passes).
void threshold(const cv::Mat& src, cv::Mat& dst, int t, std::uint8_t high = 255, cv::Range rows = cv::Range::all());

/// Otsu's threshold from a histogram: the T maximising the between-class variance of {<= T} and
/// {> T}. Computed exactly as cv::threshold(THRESH_OTSU) does, so both choose the same T. An empty
/// histogram, or one with a single occupied bin, gives 0 (as OpenCV does for a constant image).
int otsu_threshold(const Histogram& hist);

}  // namespace neopipe::kernels
