#pragma once
// 3x3 arithmetic neighbourhood: out = saturate(round(sum(w_i * p_i) / 2^shift)). PIPE's real-time
// convolution stage: integer weights, a right shift for scale, saturation to the output type.

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint conv3x3_footprint = Footprint::neighbourhood3x3;

struct Conv3x3 {
  /// Weights in reading order: NW, N, NE, W, C, E, SW, S, SE. |w| <= 65535.
  std::array<int, 9> weights{0, 0, 0, 0, 1, 0, 0, 0, 0};
  /// The weighted sum is divided by 2^shift (0..16), rounding halves up (toward +infinity).
  int shift = 0;
  Border border{};
};

/// Checks the parameters; throws KernelError with the reason.
void validate(const Conv3x3& k);

/// One output row from the three input rows around it (up, mid, down).
void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                 int width, const Conv3x3& k) noexcept;
void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::int16_t* out,
                 int width, const Conv3x3& k) noexcept;

/// src CV_8UC1; dst CV_8UC1 (saturated to 0..255) or CV_16SC1 (saturated to -32768..32767).
/// dst must not share memory with src (KernelError).
/// `dst_type` picks the output when dst is allocated here (whole-frame calls).
void conv3x3(const cv::Mat& src, cv::Mat& dst, const Conv3x3& k, int dst_type = CV_8UC1,
             cv::Range rows = cv::Range::all());

/// Handy weight sets.
Conv3x3 smooth3x3();   ///< [1 2 1; 2 4 2; 1 2 1] / 16
Conv3x3 sobel_x3x3();  ///< [-1 0 1; -2 0 2; -1 0 1], for 16-bit output
Conv3x3 sobel_y3x3();  ///< [-1 -2 -1; 0 0 0; 1 2 1], for 16-bit output

}  // namespace neopipe::kernels
