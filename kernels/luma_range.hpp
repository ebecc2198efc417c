#pragma once
// Limited-range ("TV", studio swing: black 16, white 235) luma to full range (0..255):
// out = clamp(round((y - 16) * 255 / 219), 0, 255).
//
// Why: a video decoder hands out Y'CbCr. Converted to BGR with the BT.601 matrix (as swscale and
// so cv::VideoCapture do) and back to gray with the BT.601 weights (cv::cvtColor BGR2GRAY), the
// chroma terms cancel and gray is this expansion of Y' (up to the rounding of the BGR bytes). The
// video reader applies it to the luma plane, which saves both colour conversions.

#include <cstdint>

namespace neopipe::kernels {

/// The exact formula, for tests and documentation: round half up, clamped.
constexpr std::uint8_t limited_to_full_luma_exact(int y) {
  const int num = (y - 16) * 255 * 2 + 219;  // 2 * 219 * ((y - 16) * 255 / 219 + 1/2)
  const int v = num < 0 ? 0 : num / (2 * 219);
  return static_cast<std::uint8_t>(v > 255 ? 255 : v);
}

/// The same in 16-bit fixed point, as the vector loop computes it: with d = max(y - 16, 0),
/// out = min(((d * 256 * kLumaMul) >> 16 + 64) >> 7, 255). kLumaMul / 2^15 approximates 255 / 219;
/// the constant was found by trying all candidates, and a static_assert in luma_range.cpp checks
/// that it gives the exact formula for every input.
inline constexpr std::uint16_t kLumaMul = 38155;
constexpr std::uint8_t limited_to_full_luma(std::uint8_t y) {
  const unsigned d256 = y > 16 ? (y - 16u) << 8 : 0u;
  const unsigned v = (((d256 * kLumaMul) >> 16) + 64u) >> 7;
  return static_cast<std::uint8_t>(v > 255 ? 255 : v);
}

/// out[x] = limited_to_full_luma(in[x]) for x < width; in and out may be the same row.
void limited_to_full_luma_row(const std::uint8_t* in, std::uint8_t* out, int width) noexcept;

}  // namespace neopipe::kernels
