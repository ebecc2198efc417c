#include "kernels/gray.hpp"

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {
namespace {
// BT.601 weights scaled by 2^15; they sum to exactly 2^15, so white stays 255.
constexpr int kShift = 15;
constexpr int kB = 3735;
constexpr int kG = 19235;
constexpr int kR = 9798;
constexpr int kRound = 1 << (kShift - 1);

// The vector path splits each weight w into 128 * hi + lo (lo < 128). Then, with
// H = sum(hi * p) + 128 and L = sum(lo * p), the 15-bit sum is 128 * H + L and
// (128 * H + L) >> 15 == (H + (L >> 7)) >> 8 exactly. The his sum to 255 and the los to 128, so
// H <= 255 * 255 + 128 and H + (L >> 7) <= 65408: everything stays in unsigned 16-bit lanes.
constexpr int kHiB = kB >> 7, kLoB = kB & 127;
constexpr int kHiG = kG >> 7, kLoG = kG & 127;
constexpr int kHiR = kR >> 7, kLoR = kR & 127;
static_assert(kHiB + kHiG + kHiR == 255 && kLoB + kLoG + kLoR == 128 && kRound == 128 * 128);

#if HWY_TARGET != HWY_SCALAR
namespace hn = simd::hn;

template <class D16, class V16 = hn::VFromD<D16>>
V16 gray16(D16 d16, V16 b, V16 g, V16 r) {
  const V16 hi = hn::Add(hn::Add(hn::Mul(b, hn::Set(d16, kHiB)), hn::Mul(g, hn::Set(d16, kHiG))),
                         hn::Add(hn::Mul(r, hn::Set(d16, kHiR)), hn::Set(d16, kRound >> 7)));
  const V16 lo =
      hn::Add(hn::Add(hn::Mul(b, hn::Set(d16, kLoB)), hn::Mul(g, hn::Set(d16, kLoG))), hn::Mul(r, hn::Set(d16, kLoR)));
  return hn::ShiftRight<8>(hn::Add(hi, hn::ShiftRight<7>(lo)));
}
#endif
}  // namespace

void bgr_to_gray_row(const std::uint8_t* bgr, std::uint8_t* out, int width) noexcept {
  const auto scalar = [&](size_t x0, size_t x1) {
    for (size_t x = x0; x < x1; ++x) {
      const std::uint8_t* p = bgr + 3 * x;
      out[x] = static_cast<std::uint8_t>((p[0] * kB + p[1] * kG + p[2] * kR + kRound) >> kShift);
    }
  };
#if HWY_TARGET != HWY_SCALAR
  const hn::ScalableTag<std::uint8_t> d8;
  const hn::Repartition<std::uint16_t, decltype(d8)> d16;
  const auto low_byte = hn::Set(d16, std::uint16_t{0x00FF});
  simd::point_row(
      d8, out, static_cast<size_t>(width),
      [&](size_t x) {
        hn::VFromD<decltype(d8)> b, g, r;
        hn::LoadInterleaved3(d8, bgr + 3 * x, b, g, r);
        // Even pixels are the low bytes of the 16-bit lanes, odd pixels the high bytes.
        const auto b16 = hn::BitCast(d16, b);
        const auto g16 = hn::BitCast(d16, g);
        const auto r16 = hn::BitCast(d16, r);
        const auto even = gray16(d16, hn::And(b16, low_byte), hn::And(g16, low_byte), hn::And(r16, low_byte));
        const auto odd = gray16(d16, hn::ShiftRight<8>(b16), hn::ShiftRight<8>(g16), hn::ShiftRight<8>(r16));
        return hn::BitCast(d8, hn::Or(even, hn::ShiftLeft<8>(odd)));
      },
      scalar);
#else
  scalar(0, static_cast<size_t>(width));
#endif
}

void bgr_to_gray(const cv::Mat& src, cv::Mat& dst, cv::Range rows) {
  detail::require_type(src, CV_8UC3, "gray input");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) bgr_to_gray_row(src.ptr<std::uint8_t>(y), dst.ptr<std::uint8_t>(y), src.cols);
}

}  // namespace neopipe::kernels
