#include "kernels/gray.hpp"

#include "kernels/rows.hpp"

namespace neopipe::kernels {
namespace {
// BT.601 weights scaled by 2^15; they sum to exactly 2^15, so white stays 255.
constexpr int kShift = 15;
constexpr int kB = 3735;
constexpr int kG = 19235;
constexpr int kR = 9798;
constexpr int kRound = 1 << (kShift - 1);
}  // namespace

void bgr_to_gray_row(const std::uint8_t* bgr, std::uint8_t* out, int width) noexcept {
  for (int x = 0; x < width; ++x) {
    const std::uint8_t* p = bgr + std::ptrdiff_t{3} * x;
    out[x] = static_cast<std::uint8_t>((p[0] * kB + p[1] * kG + p[2] * kR + kRound) >> kShift);
  }
}

void bgr_to_gray(const cv::Mat& src, cv::Mat& dst, cv::Range rows) {
  detail::require_type(src, CV_8UC3, "gray input");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) bgr_to_gray_row(src.ptr<std::uint8_t>(y), dst.ptr<std::uint8_t>(y), src.cols);
}

}  // namespace neopipe::kernels
