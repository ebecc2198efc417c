#include "kernels/bool3x3.hpp"

#include <array>

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {

BoolTable::BoolTable(const std::bitset<512>& bits) : bits_(bits) {
  if (bits_.count() == 1 && bits_[511]) {
    kind_ = Kind::erode;
  } else if (bits_.count() == 511 && !bits_[0]) {
    kind_ = Kind::dilate;
  }
  for (size_t i = 0; i < 512; ++i) {
    if (bits_[i]) packed_[i / 8] = static_cast<std::uint8_t>(packed_[i / 8] | (1U << (i % 8)));
  }
}

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

namespace {

#if HWY_TARGET != HWY_SCALAR
namespace hn = simd::hn;
using D8 = hn::ScalableTag<std::uint8_t>;
using V8 = hn::VFromD<D8>;

/// Erosion and dilation: a pixel is set where the minimum (erode) or maximum (dilate) of its nine
/// neighbours is non-zero.
template <bool kErode, class ScalarFn>
void interior_min_max(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                      size_t width, std::uint8_t high, ScalarFn&& scalar) {
  const D8 d;
  const V8 vhigh = hn::Set(d, high);
  const auto combine = [](V8 a, V8 b) { return kErode ? hn::Min(a, b) : hn::Max(a, b); };
  const auto column = [&](size_t x) {
    return combine(combine(hn::LoadU(d, up + x), hn::LoadU(d, mid + x)), hn::LoadU(d, down + x));
  };
  simd::interior_blocks(
      width, hn::Lanes(d),
      [&](size_t x) {
        const V8 m = combine(combine(column(x - 1), column(x)), column(x + 1));
        hn::StoreU(hn::IfThenZeroElse(hn::Eq(m, hn::Zero(d)), vhigh), d, out + x);
      },
      scalar);
}

/// Any table, with the lookup done by byte shuffles. Index bits 0-2 (the row above) pick a bit
/// within a table byte; bits 3-6 pick a byte within a 16-byte quarter of the table; bits 7-8 (the
/// lower row's centre and right pixels) pick the quarter.
template <class ScalarFn>
void interior_table(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                    size_t width, const Bool3x3& k, ScalarFn&& scalar) {
  const D8 d;
  const auto& packed = k.table.packed();
  const V8 quarter0 = hn::LoadDup128(d, packed.data());
  const V8 quarter1 = hn::LoadDup128(d, packed.data() + 16);
  const V8 quarter2 = hn::LoadDup128(d, packed.data() + 32);
  const V8 quarter3 = hn::LoadDup128(d, packed.data() + 48);
  alignas(16) static constexpr std::uint8_t kBit[16] = {1, 2, 4, 8, 16, 32, 64, 128, 0, 0, 0, 0, 0, 0, 0, 0};
  const V8 bit_of = hn::LoadDup128(d, kBit);
  const V8 zero = hn::Zero(d);
  const V8 vhigh = hn::Set(d, k.high);
  std::array<V8, 4> weight;
  for (size_t i = 0; i < 4; ++i) weight[i] = hn::Set(d, static_cast<std::uint8_t>(1U << i));
  simd::interior_blocks(
      width, hn::Lanes(d),
      [&](size_t x) {
        const auto clear = [&](const std::uint8_t* row, size_t xx) { return hn::Eq(hn::LoadU(d, row + xx), zero); };
        const auto bit = [&](const std::uint8_t* row, size_t xx, size_t b) {
          return hn::IfThenZeroElse(clear(row, xx), weight[b]);
        };
        const V8 bit_in_byte = hn::Or(hn::Or(bit(up, x - 1, 0), bit(up, x, 1)), bit(up, x + 1, 2));
        const V8 byte_in_quarter =
            hn::Or(hn::Or(bit(mid, x - 1, 0), bit(mid, x, 1)), hn::Or(bit(mid, x + 1, 2), bit(down, x - 1, 3)));
        const auto south_clear = clear(down, x);
        const auto south_east_clear = clear(down, x + 1);
        const V8 q0 = hn::TableLookupBytes(quarter0, byte_in_quarter);
        const V8 q1 = hn::TableLookupBytes(quarter1, byte_in_quarter);
        const V8 q2 = hn::TableLookupBytes(quarter2, byte_in_quarter);
        const V8 q3 = hn::TableLookupBytes(quarter3, byte_in_quarter);
        const V8 byte =
            hn::IfThenElse(south_east_clear, hn::IfThenElse(south_clear, q0, q1), hn::IfThenElse(south_clear, q2, q3));
        const auto set = hn::TestBit(byte, hn::TableLookupBytes(bit_of, bit_in_byte));
        hn::StoreU(hn::IfThenElseZero(set, vhigh), d, out + x);
      },
      scalar);
}
#endif

}  // namespace

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
  const auto column = [&](size_t x) {
    return (up[x] != 0 ? 1U : 0U) | (mid[x] != 0 ? 8U : 0U) | (down[x] != 0 ? 64U : 0U);
  };
  const auto scalar = [&](size_t x0, size_t x1) {
    // Columns x0 - 1 and x0 in the centre and right positions: the first step makes x = x0.
    unsigned idx = (column(x0 - 1) << 1) | (column(x0) << 2);
    for (size_t x = x0; x < x1; ++x) {
      idx = ((idx >> 1) & 0b011011011U) | (column(x + 1) << 2);
      out[x] = bits[idx] ? k.high : std::uint8_t{0};
    }
  };
  if (width < 3) return;
  const auto n = static_cast<size_t>(width);
#if HWY_TARGET != HWY_SCALAR
  switch (k.table.kind()) {
    case BoolTable::Kind::erode:
      return interior_min_max<true>(up, mid, down, out, n, k.high, scalar);
    case BoolTable::Kind::dilate:
      return interior_min_max<false>(up, mid, down, out, n, k.high, scalar);
    case BoolTable::Kind::general:
      return interior_table(up, mid, down, out, n, k, scalar);
  }
#else
  scalar(1, n - 1);
#endif
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
