#pragma once
// Two-input pixel arithmetic and logic: PIPE's ALU between a stage's two images.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string_view>

#include "kernels/types.hpp"

namespace neopipe::kernels {

/// add and sub saturate to 0..255 (as cv::add / cv::subtract on CV_8U); absdiff is |a - b|.
enum class AluOp { add, sub, absdiff, min, max, bit_and, bit_or, bit_xor };
inline constexpr Footprint alu_footprint = Footprint::point;

std::string_view to_string(AluOp op);
/// "add", "sub", "absdiff", "min", "max", "and", "or", "xor".
std::optional<AluOp> alu_op_from_string(std::string_view name);

void alu_row(AluOp op, const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out, int width) noexcept;

/// dst = a op b on `rows`; a, b and dst are CV_8UC1 of one size.
void alu(AluOp op, const cv::Mat& a, const cv::Mat& b, cv::Mat& dst, cv::Range rows = cv::Range::all());

}  // namespace neopipe::kernels
