#include "kernels/convert.hpp"

#include <algorithm>
#include <cstdlib>

#include "kernels/rows.hpp"

namespace neopipe::kernels {

void convert_s16_row(const std::int16_t* in, std::uint8_t* out, int width, const ConvertS16& c) noexcept {
  const int shift = c.shift;
  const int bias = shift > 0 ? 1 << (shift - 1) : 0;
  if (c.absolute) {
    for (int x = 0; x < width; ++x)
      out[x] = static_cast<std::uint8_t>(std::min((std::abs(int{in[x]}) + bias) >> shift, 255));
  } else {
    for (int x = 0; x < width; ++x)
      out[x] = static_cast<std::uint8_t>(std::clamp((int{in[x]} + bias) >> shift, 0, 255));
  }
}

void convert_s16(const cv::Mat& src, cv::Mat& dst, const ConvertS16& c, cv::Range rows) {
  detail::require_type(src, CV_16SC1, "convert input");
  detail::require(c.shift >= 0 && c.shift <= 15, "convert: shift must lie in 0..15");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y)
    convert_s16_row(src.ptr<std::int16_t>(y), dst.ptr<std::uint8_t>(y), src.cols, c);
}

}  // namespace neopipe::kernels
