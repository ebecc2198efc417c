#pragma once
// 16-bit signed to 8-bit: out = saturate(round((abs ? |v| : v) / 2^shift)). Brings the 16-bit
// output of a 3x3 arithmetic stage (e.g. a Sobel gradient) back into 8-bit images.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint convert_footprint = Footprint::point;

struct ConvertS16 {
  bool absolute = true;  ///< take |v| first (gradient magnitude); otherwise negatives become 0
  int shift = 0;         ///< 0..15; halves round toward +infinity, as in conv3x3
};

void convert_s16_row(const std::int16_t* in, std::uint8_t* out, int width, const ConvertS16& c) noexcept;

/// src CV_16SC1, dst CV_8UC1.
void convert_s16(const cv::Mat& src, cv::Mat& dst, const ConvertS16& c, cv::Range rows = cv::Range::all());

}  // namespace neopipe::kernels
