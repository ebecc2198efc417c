#include "kernels/convert.hpp"

#include <algorithm>
#include <cstdlib>

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {

void convert_s16_row(const std::int16_t* in, std::uint8_t* out, int width, const ConvertS16& c) noexcept {
  const int shift = c.shift;
  const int bias = shift > 0 ? 1 << (shift - 1) : 0;
  const auto scalar = [&](size_t x0, size_t x1) {
    if (c.absolute) {
      for (size_t x = x0; x < x1; ++x)
        out[x] = static_cast<std::uint8_t>(std::min((std::abs(int{in[x]}) + bias) >> shift, 255));
    } else {
      for (size_t x = x0; x < x1; ++x)
        out[x] = static_cast<std::uint8_t>(std::clamp((int{in[x]} + bias) >> shift, 0, 255));
    }
  };
#if HWY_TARGET != HWY_SCALAR
  namespace hn = simd::hn;
  const hn::ScalableTag<std::int16_t> di;
  const hn::RebindToUnsigned<decltype(di)> du;
  const hn::Rebind<std::uint8_t, decltype(di)> d8;  // one output byte per 16-bit lane
  const auto n = static_cast<size_t>(width);
  if (c.absolute) {
    // |v| as unsigned 16 bits is exact even for -32768, and |v| + bias <= 32768 + 16384 fits.
    const auto vbias = hn::Set(du, static_cast<std::uint16_t>(bias));
    const auto v255 = hn::Set(du, std::uint16_t{255});
    simd::point_row(
        d8, out, n,
        [&](size_t x) {
          const auto mag = hn::BitCast(du, hn::Abs(hn::LoadU(di, in + x)));
          const auto v = hn::Min(hn::ShiftRightSame(hn::Add(mag, vbias), shift), v255);
          return hn::DemoteTo(d8, hn::BitCast(di, v));
        },
        scalar);
  } else if (shift == 0) {
    simd::point_row(
        d8, out, n, [&](size_t x) { return hn::DemoteTo(d8, hn::LoadU(di, in + x)); }, scalar);
  } else {
    // (v + 2^(s-1)) >> s == ((v >> (s-1)) + 1) >> 1, which cannot overflow 16 bits except for
    // v = 32767 at s = 1; there the saturated sum gives 16383 for 16384, and both become 255.
    const auto one = hn::Set(di, std::int16_t{1});
    simd::point_row(
        d8, out, n,
        [&](size_t x) {
          const auto halved = hn::ShiftRightSame(hn::LoadU(di, in + x), shift - 1);
          return hn::DemoteTo(d8, hn::ShiftRight<1>(hn::SaturatedAdd(halved, one)));
        },
        scalar);
  }
#else
  scalar(0, static_cast<size_t>(width));
#endif
}

void convert_s16(const cv::Mat& src, cv::Mat& dst, const ConvertS16& c, cv::Range rows) {
  detail::require_type(src, CV_16SC1, "convert input");
  detail::require(c.shift >= 0 && c.shift <= 15, "convert: shift must lie in 0..15");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y)
    convert_s16_row(src.ptr<std::int16_t>(y), dst.ptr<std::uint8_t>(y), src.cols, c);
}

}  // namespace neopipe::kernels
