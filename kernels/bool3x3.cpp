#include "kernels/bool3x3.hpp"

#include <array>

#include "kernels/rows.hpp"

namespace neopipe::kernels {

BoolTable BoolTable::from_function(const std::function<bool(unsigned)>& f) {
  std::bitset<512> bits;
  for (unsigned i = 0; i < 512; ++i) bits[i] = f(i);
  return BoolTable(bits);
}

BoolTable erode_table() {
  std::bitset<512> bits;
  bits[511] = true;
  return BoolTable(bits);
}

BoolTable dilate_table() {
  std::bitset<512> bits;
  bits.set();
  bits[0] = false;
  return BoolTable(bits);
}

BoolTable hit_or_miss_table(std::string_view pattern) {
  unsigned must_set = 0;
  unsigned must_clear = 0;
  unsigned k = 0;
  for (const char c : pattern) {
    if (c == ' ' || c == '\t' || c == '\n' || c == ',') continue;
    if (k >= 9) throw KernelError("hit-or-miss pattern has more than nine cells");
    if (c == '1') {
      must_set |= 1U << k;
    } else if (c == '0') {
      must_clear |= 1U << k;
    } else if (c != 'x' && c != 'X' && c != '.') {
      throw KernelError(std::string("hit-or-miss pattern: unexpected character '") + c + "' (use 1, 0 or x)");
    }
    ++k;
  }
  if (k != 9) throw KernelError("hit-or-miss pattern must have nine cells, got " + std::to_string(k));
  return BoolTable::from_function([=](unsigned i) { return (i & must_set) == must_set && (i & must_clear) == 0; });
}

void bool3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                 int width, const Bool3x3& k) noexcept {
  const auto& bits = k.table.bits();
  const Border border{k.border.mode, k.border.value != 0 ? 1 : 0};
  const auto pixel = [&](int x, const std::array<int, 9>& p) {
    unsigned idx = 0;
    for (unsigned i = 0; i < 9; ++i) idx |= (p[i] != 0 ? 1U : 0U) << i;
    out[x] = bits[idx] ? k.high : std::uint8_t{0};
  };
  detail::border_pixels(detail::RowTriple<std::uint8_t>{up, mid, down}, width, border, pixel);
  // Slide the 3x3 window: the next index drops the left column (bits 0, 3, 6), shifts the rest
  // left-ward and brings in the new right column at bits 2, 5, 8.
  const auto column = [&](int x) {
    return (up[x] != 0 ? 1U : 0U) | (mid[x] != 0 ? 8U : 0U) | (down[x] != 0 ? 64U : 0U);
  };
  if (width < 3) return;
  // Column 0 in the centre position and column 1 on the right: the first step makes x = 1.
  unsigned idx = (column(0) << 1) | (column(1) << 2);
  for (int x = 1; x < width - 1; ++x) {
    idx = ((idx >> 1) & 0b011011011U) | (column(x + 1) << 2);
    out[x] = bits[idx] ? k.high : std::uint8_t{0};
  }
}

void bool3x3(const cv::Mat& src, cv::Mat& dst, const Bool3x3& k, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "bool3x3 input");
  detail::require_distinct(src, dst, "bool3x3");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  const Border border{k.border.mode, k.border.value != 0 ? 255 : 0};
  const detail::NeighbourRows<std::uint8_t> nrows(src, border);
  for (int y = r.start; y < r.end; ++y) {
    const auto t = nrows.at(y);
    bool3x3_row(t.up, t.mid, t.down, dst.ptr<std::uint8_t>(y), src.cols, k);
  }
}

}  // namespace neopipe::kernels
