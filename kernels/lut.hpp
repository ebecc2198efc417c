#pragma once
// Point look-up table: out = table[in]. PIPE's per-stage LUT; any function of one 8-bit pixel.

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "kernels/types.hpp"

namespace neopipe::kernels {

using Lut = std::array<std::uint8_t, 256>;
inline constexpr Footprint lut_footprint = Footprint::point;

void lut_row(const std::uint8_t* in, std::uint8_t* out, int width, const Lut& table) noexcept;

/// dst = table[src] on `rows` (all rows by default). src and dst are CV_8UC1 of the same size.
void lut(const cv::Mat& src, cv::Mat& dst, const Lut& table, cv::Range rows = cv::Range::all());

Lut identity_lut();

}  // namespace neopipe::kernels
