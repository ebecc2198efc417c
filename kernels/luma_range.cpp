#include "kernels/luma_range.hpp"

#include <cstddef>

#include "kernels/simd.hpp"

namespace neopipe::kernels {
namespace {

constexpr bool fixed_point_is_exact() {
  for (int y = 0; y < 256; ++y) {
    if (limited_to_full_luma(static_cast<std::uint8_t>(y)) != limited_to_full_luma_exact(y)) return false;
  }
  return true;
}
static_assert(fixed_point_is_exact(), "kLumaMul must give round((y - 16) * 255 / 219) for every y");

#if HWY_TARGET != HWY_SCALAR
namespace hn = simd::hn;

// `d256` holds (y - 16) * 256, saturated at 0 (at most 239 * 256, so it fits in 16 bits); the
// result is at most 278 before the clamp.
template <class D16, class V16 = hn::VFromD<D16>>
V16 expand16(D16 d16, V16 d256) {
  const V16 scaled = hn::MulHigh(d256, hn::Set(d16, kLumaMul));
  return hn::Min(hn::ShiftRight<7>(hn::Add(scaled, hn::Set(d16, std::uint16_t{64}))), hn::Set(d16, std::uint16_t{255}));
}
#endif

}  // namespace

void limited_to_full_luma_row(const std::uint8_t* in, std::uint8_t* out, int width) noexcept {
  const auto scalar = [&](std::size_t x0, std::size_t x1) {
    for (std::size_t x = x0; x < x1; ++x) out[x] = limited_to_full_luma(in[x]);
  };
#if HWY_TARGET != HWY_SCALAR
  const hn::ScalableTag<std::uint8_t> d8;
  const hn::Repartition<std::uint16_t, decltype(d8)> d16;
  const auto high_byte = hn::Set(d16, std::uint16_t{0xFF00});
  const auto black = hn::Set(d16, std::uint16_t{16 << 8});
  simd::point_row(
      d8, out, static_cast<std::size_t>(width),
      [&](std::size_t x) {
        const auto v = hn::BitCast(d16, hn::LoadU(d8, in + x));
        // Even pixels are the low bytes of the 16-bit lanes, odd pixels the high bytes; each is
        // moved to the high byte, which is y * 256, and 16 * 256 taken off with saturation.
        const auto even = expand16(d16, hn::SaturatedSub(hn::ShiftLeft<8>(v), black));
        const auto odd = expand16(d16, hn::SaturatedSub(hn::And(v, high_byte), black));
        return hn::BitCast(d8, hn::Or(even, hn::ShiftLeft<8>(odd)));
      },
      scalar);
#else
  scalar(0, static_cast<std::size_t>(width));
#endif
}

}  // namespace neopipe::kernels
