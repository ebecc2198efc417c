#include "kernels/lut2.hpp"

#include "kernels/rows.hpp"

namespace neopipe::kernels {

Lut2::Lut2() : table_(65536) {
  for (size_t i = 0; i < table_.size(); ++i) table_[i] = static_cast<std::uint8_t>(i >> 8);
}

Lut2 Lut2::from_function(const std::function<std::uint8_t(int, int)>& f) {
  Lut2 t;
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) t.table_[static_cast<size_t>(a) * 256 + static_cast<size_t>(b)] = f(a, b);
  }
  return t;
}

void lut2_row(const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out, int width, const Lut2& table) noexcept {
  const std::uint8_t* t = table.data();
  for (int x = 0; x < width; ++x) out[x] = t[(static_cast<unsigned>(a[x]) << 8) | b[x]];
}

void lut2(const cv::Mat& a, const cv::Mat& b, cv::Mat& dst, const Lut2& table, cv::Range rows) {
  detail::require_type(a, CV_8UC1, "lut2 input a");
  detail::require_type(b, CV_8UC1, "lut2 input b");
  detail::require_same_size(a, b, "lut2 inputs");
  const cv::Range r = detail::output_rows(dst, a.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) {
    lut2_row(a.ptr<std::uint8_t>(y), b.ptr<std::uint8_t>(y), dst.ptr<std::uint8_t>(y), a.cols, table);
  }
}

}  // namespace neopipe::kernels
