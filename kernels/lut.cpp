#include "kernels/lut.hpp"

#include <numeric>

#include "kernels/rows.hpp"

namespace neopipe::kernels {

void lut_row(const std::uint8_t* in, std::uint8_t* out, int width, const Lut& table) noexcept {
  for (int x = 0; x < width; ++x) out[x] = table[in[x]];
}

void lut(const cv::Mat& src, cv::Mat& dst, const Lut& table, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "lut input");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) lut_row(src.ptr<std::uint8_t>(y), dst.ptr<std::uint8_t>(y), src.cols, table);
}

Lut identity_lut() {
  Lut t{};
  std::iota(t.begin(), t.end(), std::uint8_t{0});
  return t;
}

}  // namespace neopipe::kernels
