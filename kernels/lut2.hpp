#pragma once
// Two-input table: out = table[a][b], any function of two 8-bit pixels (PIPE's 64K-entry
// "two-valued function"). A recursive running average is one such table.

#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint lut2_footprint = Footprint::point;

class Lut2 {
 public:
  /// The identity on `a`: table[a][b] = a.
  Lut2();
  /// table[a][b] = f(a, b) for every pair; f's result is used as is (it must lie in 0..255).
  static Lut2 from_function(const std::function<std::uint8_t(int a, int b)>& f);

  std::uint8_t operator()(std::uint8_t a, std::uint8_t b) const noexcept {
    return table_[(static_cast<size_t>(a) << 8) | b];
  }
  const std::uint8_t* data() const noexcept { return table_.data(); }
  std::uint8_t& at(int a, int b) { return table_.at((static_cast<size_t>(a) << 8) | static_cast<size_t>(b)); }

 private:
  std::vector<std::uint8_t> table_;  // 65,536 entries, row a, column b
};

void lut2_row(const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out, int width, const Lut2& table) noexcept;

/// dst = table(a, b) on `rows`; a, b and dst are CV_8UC1 of one size.
void lut2(const cv::Mat& a, const cv::Mat& b, cv::Mat& dst, const Lut2& table, cv::Range rows = cv::Range::all());

}  // namespace neopipe::kernels
