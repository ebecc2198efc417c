#include "kernels/conv3x3.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {
namespace {

template <class Out>
Out saturate(int v) {
  return static_cast<Out>(std::clamp(v, int{std::numeric_limits<Out>::min()}, int{std::numeric_limits<Out>::max()}));
}

int rounding_bias(int shift) {
  return shift > 0 ? 1 << (shift - 1) : 0;
}

// An arithmetic right shift floors, so adding half first rounds halves toward +infinity.
template <class Out>
Out finish(int acc, int shift) {
  return saturate<Out>((acc + rounding_bias(shift)) >> shift);
}

/// Whether acc + bias lies in -32768..32767 for every input. Then 16-bit lanes give the exact sum:
/// products and partial sums may wrap, but wrapping arithmetic is exact modulo 2^16, so a final
/// value that fits is right. True for the smooth preset and Sobel, not for large weights.
bool sums_fit_16_bits(const Conv3x3& k) {
  int pos = 0;
  int neg = 0;
  for (int w : k.weights) (w > 0 ? pos : neg) += 255 * std::abs(w);
  const int bias = rounding_bias(k.shift);
  return pos + bias <= 32767 && bias - neg >= -32768;
}

template <class Out>
void interior_scalar(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, Out* out, size_t x0,
                     size_t x1, const Conv3x3& k) {
  const auto& w = k.weights;
  for (size_t x = x0; x < x1; ++x) {
    const int acc = w[0] * up[x - 1] + w[1] * up[x] + w[2] * up[x + 1] + w[3] * mid[x - 1] + w[4] * mid[x] +
                    w[5] * mid[x + 1] + w[6] * down[x - 1] + w[7] * down[x] + w[8] * down[x + 1];
    out[x] = finish<Out>(acc, k.shift);
  }
}

#if HWY_TARGET != HWY_SCALAR
namespace hn = simd::hn;

/// 16-bit sums (see sums_fit_16_bits) on a whole vector of bytes at once: each 16-bit lane holds
/// an even pixel in its low byte and the odd pixel after it in its high byte, so the even and odd
/// outputs are two sums over the same three loads per row, with no widening shuffles. For the
/// even output at x + 2j the left, centre and right neighbours are the low bytes at x - 1 and x
/// and the high byte at x; for the odd output at x + 2j + 1 they are the low byte at x and the high
/// bytes at x and x + 1.
template <class Out>
void interior_16(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, Out* out, size_t width,
                 const Conv3x3& k) {
  const hn::ScalableTag<std::uint8_t> d8;
  const hn::Repartition<std::uint16_t, decltype(d8)> du;
  const hn::Repartition<std::int16_t, decltype(d8)> di;
  using V = hn::VFromD<decltype(di)>;
  std::array<V, 9> w;
  for (size_t i = 0; i < 9; ++i) w[i] = hn::Set(di, static_cast<std::int16_t>(k.weights[i]));
  const V bias = hn::Set(di, static_cast<std::int16_t>(rounding_bias(k.shift)));
  const auto low_byte = hn::Set(du, std::uint16_t{0x00FF});
  const std::array<const std::uint8_t*, 3> rows{up, mid, down};
  const int shift = k.shift;
  simd::interior_blocks(
      width, hn::Lanes(d8),
      [&](size_t x) {
        V even = bias;
        V odd = bias;
        for (size_t r = 0; r < 3; ++r) {
          const auto left = hn::BitCast(du, hn::LoadU(d8, rows[r] + x - 1));
          const auto centre = hn::BitCast(du, hn::LoadU(d8, rows[r] + x));
          const auto right = hn::BitCast(du, hn::LoadU(d8, rows[r] + x + 1));
          const V left_lo = hn::BitCast(di, hn::And(left, low_byte));
          const V centre_lo = hn::BitCast(di, hn::And(centre, low_byte));
          const V centre_hi = hn::BitCast(di, hn::ShiftRight<8>(centre));
          const V right_hi = hn::BitCast(di, hn::ShiftRight<8>(right));
          even = hn::Add(even, hn::Add(hn::Add(hn::Mul(left_lo, w[3 * r]), hn::Mul(centre_lo, w[3 * r + 1])),
                                       hn::Mul(centre_hi, w[3 * r + 2])));
          odd = hn::Add(odd, hn::Add(hn::Add(hn::Mul(centre_lo, w[3 * r]), hn::Mul(centre_hi, w[3 * r + 1])),
                                     hn::Mul(right_hi, w[3 * r + 2])));
        }
        even = hn::ShiftRightSame(even, shift);
        odd = hn::ShiftRightSame(odd, shift);
        if constexpr (std::is_same_v<Out, std::uint8_t>) {
          const V zero = hn::Zero(di);
          const V top = hn::Set(di, std::int16_t{255});
          const auto e = hn::BitCast(du, hn::Min(hn::Max(even, zero), top));
          const auto o = hn::BitCast(du, hn::Min(hn::Max(odd, zero), top));
          hn::StoreU(hn::BitCast(d8, hn::Or(e, hn::ShiftLeft<8>(o))), d8, out + x);
        } else {
          hn::StoreInterleaved2(even, odd, di, out + x);
        }
      },
      [&](size_t x0, size_t x1) { interior_scalar(up, mid, down, out, x0, x1, k); });
}

/// 32-bit sums, exact for any valid weights (|sum| <= 9 * 65535 * 255 < 2^31).
template <class Out>
void interior_32(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, Out* out, size_t width,
                 const Conv3x3& k) {
  const hn::ScalableTag<std::int32_t> d32;
  const hn::Rebind<std::uint8_t, decltype(d32)> d8;
  const hn::Rebind<Out, decltype(d32)> dout;
  using V = hn::VFromD<decltype(d32)>;
  std::array<V, 9> w;
  for (size_t i = 0; i < 9; ++i) w[i] = hn::Set(d32, k.weights[i]);
  const V bias = hn::Set(d32, rounding_bias(k.shift));
  const std::array<const std::uint8_t*, 3> rows{up, mid, down};
  const int shift = k.shift;
  simd::interior_blocks(
      width, hn::Lanes(d32),
      [&](size_t x) {
        V acc = bias;
        for (size_t r = 0; r < 3; ++r) {
          for (size_t c = 0; c < 3; ++c) {
            const V p = hn::PromoteTo(d32, hn::LoadU(d8, rows[r] + x + c - 1));
            acc = hn::Add(acc, hn::Mul(p, w[3 * r + c]));
          }
        }
        // Clamped before DemoteTo: Highway 1.0's i32 -> u8 demotion on AVX2 does not saturate every
        // out-of-range value (tests caught sums above 32767 wrapping).
        const V lo = hn::Set(d32, int{std::numeric_limits<Out>::min()});
        const V hi = hn::Set(d32, int{std::numeric_limits<Out>::max()});
        const V clamped = hn::Min(hn::Max(hn::ShiftRightSame(acc, shift), lo), hi);
        hn::StoreU(hn::DemoteTo(dout, clamped), dout, out + x);
      },
      [&](size_t x0, size_t x1) { interior_scalar(up, mid, down, out, x0, x1, k); });
}
#endif

template <class Out>
void row_impl(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, Out* out, int width,
              const Conv3x3& k) {
  const auto& w = k.weights;
  detail::border_pixels(detail::RowTriple<std::uint8_t>{up, mid, down}, width, k.border,
                        [&](int x, const std::array<int, 9>& p) {
                          int acc = 0;
                          for (size_t i = 0; i < 9; ++i) acc += w[i] * p[i];
                          out[x] = finish<Out>(acc, k.shift);
                        });
  const auto n = static_cast<size_t>(width);
#if HWY_TARGET != HWY_SCALAR
  if (sums_fit_16_bits(k)) {
    interior_16(up, mid, down, out, n, k);
  } else {
    interior_32(up, mid, down, out, n, k);
  }
#else
  if (n > 2) interior_scalar(up, mid, down, out, 1, n - 1, k);
#endif
}

template <class Out>
void frame_impl(const cv::Mat& src, cv::Mat& dst, const Conv3x3& k, cv::Range r) {
  const detail::NeighbourRows<std::uint8_t> rows(src, k.border);
  for (int y = r.start; y < r.end; ++y) {
    const auto t = rows.at(y);
    conv3x3_row(t.up, t.mid, t.down, dst.ptr<Out>(y), src.cols, k);
  }
}

}  // namespace

void validate(const Conv3x3& k) {
  for (int w : k.weights) {
    detail::require(std::abs(w) <= 65535, "conv3x3: weights must lie in -65535..65535");
  }
  detail::require(k.shift >= 0 && k.shift <= 16, "conv3x3: shift must lie in 0..16");
  detail::require(k.border.mode != BorderMode::constant || (k.border.value >= 0 && k.border.value <= 255),
                  "conv3x3: the constant border value must lie in 0..255");
}

void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                 int width, const Conv3x3& k) noexcept {
  row_impl(up, mid, down, out, width, k);
}

void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::int16_t* out,
                 int width, const Conv3x3& k) noexcept {
  row_impl(up, mid, down, out, width, k);
}

void conv3x3(const cv::Mat& src, cv::Mat& dst, const Conv3x3& k, int dst_type, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "conv3x3 input");
  detail::require_distinct(src, dst, "conv3x3");
  validate(k);
  if (rows != cv::Range::all() && !dst.empty()) dst_type = dst.type();
  detail::require(dst_type == CV_8UC1 || dst_type == CV_16SC1, "conv3x3: output must be CV_8UC1 or CV_16SC1");
  const cv::Range r = detail::output_rows(dst, src.size(), dst_type, rows);
  if (dst_type == CV_8UC1) {
    frame_impl<std::uint8_t>(src, dst, k, r);
  } else {
    frame_impl<std::int16_t>(src, dst, k, r);
  }
}

Conv3x3 smooth3x3() {
  return {{1, 2, 1, 2, 4, 2, 1, 2, 1}, 4, {}};
}
Conv3x3 sobel_x3x3() {
  return {{-1, 0, 1, -2, 0, 2, -1, 0, 1}, 0, {}};
}
Conv3x3 sobel_y3x3() {
  return {{-1, -2, -1, 0, 0, 0, 1, 2, 1}, 0, {}};
}

}  // namespace neopipe::kernels
