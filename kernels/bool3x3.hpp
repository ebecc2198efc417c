#pragma once
// 3x3 Boolean neighbourhood: PIPE's binary neighbourhood stage. The nine "set" bits around a pixel
// form an index 0..511 into a table that says whether the output pixel is set. Erosion, dilation,
// hit-or-miss, thinning steps and so on are all just tables.
//
// Bit k of the index is the pixel at position k in reading order:
//
//     bit 0 (NW)  bit 1 (N)  bit 2 (NE)
//     bit 3 (W)   bit 4 (C)  bit 5 (E)
//     bit 6 (SW)  bit 7 (S)  bit 8 (SE)
//
// A pixel is "set" when it is non-zero. Output pixels are `high` (default 255) or 0.

#include <array>
#include <bitset>
#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint bool3x3_footprint = Footprint::neighbourhood3x3;

class BoolTable {
 public:
  /// Tables the kernel recognises and runs as a plain minimum or maximum over the neighbourhood.
  enum class Kind { general, erode, dilate };

  BoolTable() : BoolTable(std::bitset<512>{}) {}
  explicit BoolTable(const std::bitset<512>& bits);
  static BoolTable from_function(const std::function<bool(unsigned index)>& f);

  bool operator[](unsigned index) const { return bits_[index]; }
  const std::bitset<512>& bits() const { return bits_; }
  /// erode_table() or dilate_table(), however they were built; otherwise general.
  Kind kind() const noexcept { return kind_; }
  /// The table as 64 bytes, entry i at bit i % 8 of byte i / 8, ready for byte-shuffle lookups.
  const std::array<std::uint8_t, 64>& packed() const noexcept { return packed_; }

 private:
  // The table never changes after construction, so what the kernel needs is derived here once
  // rather than on every row.
  std::bitset<512> bits_;
  Kind kind_ = Kind::general;
  std::array<std::uint8_t, 64> packed_{};
};

/// Set where all nine pixels are set: erosion by a 3x3 square.
BoolTable erode_table();
/// Set where any of the nine pixels is set: dilation by a 3x3 square.
BoolTable dilate_table();
/// Hit-or-miss: `pattern` has nine characters in reading order ('1' must be set, '0' must be
/// clear, 'x' or '.' either); spaces are ignored, so "1x0 110 x0x" is valid. Throws KernelError.
BoolTable hit_or_miss_table(std::string_view pattern);

struct Bool3x3 {
  BoolTable table;
  std::uint8_t high = 255;
  /// Outside the image: replicate the edge, or a constant (value != 0 means set).
  Border border{};
};

void bool3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                 int width, const Bool3x3& k) noexcept;

/// src and dst CV_8UC1; dst must not share memory with src (KernelError).
void bool3x3(const cv::Mat& src, cv::Mat& dst, const Bool3x3& k, cv::Range rows = cv::Range::all());

}  // namespace neopipe::kernels
