#pragma once
// Colour to gray, ITU-R BT.601 luma, bit-exact with cv::cvtColor(COLOR_BGR2GRAY) on 8-bit images.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint gray_footprint = Footprint::point;

void bgr_to_gray_row(const std::uint8_t* bgr, std::uint8_t* out, int width) noexcept;

/// dst (CV_8UC1) = 0.114 B + 0.587 G + 0.299 R, in 15-bit fixed point rounded as OpenCV does.
void bgr_to_gray(const cv::Mat& src, cv::Mat& dst, cv::Range rows = cv::Range::all());

}  // namespace neopipe::kernels
