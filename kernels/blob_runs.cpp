#include "kernels/blob_runs.hpp"

#include <hwy/highway.h>

#include <algorithm>
#include <cstring>

namespace neopipe::kernels::detail {
namespace {

namespace hn = hwy::HWY_NAMESPACE;

// Capped at 64 lanes so that the foreground mask of one vector fits a uint64_t.
using D8 = hn::CappedTag<std::uint8_t, 64>;

template <class M>
HWY_INLINE std::uint64_t mask_bits(D8 d, M mask) {
  std::uint8_t bytes[8] = {};  // StoreMaskBits may write up to 8 bytes
  hn::StoreMaskBits(d, mask, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  return bits;
}

// Foreground bits of pixels [x, x + count) of a row of `width` pixels, bit i for pixel x + i;
// count <= 64, and a word shorter than 64 ends the row. Reads only inside the row.
HWY_INLINE std::uint64_t foreground_word(D8 d, const std::uint8_t* row, int width, int x, int count,
                                         const hn::VFromD<D8>& t) {
  const int n = static_cast<int>(hn::Lanes(d));
  std::uint64_t bits = 0;
  int k = 0;
  for (; k + n <= count; k += n) bits |= mask_bits(d, hn::LoadU(d, row + x + k) > t) << k;
  if (k < count) {
    const int rem = count - k;
    std::uint64_t tail = 0;
    if (width >= n) {
      // The row's last whole vector overlaps pixels already seen; their bits are shifted out.
      tail = mask_bits(d, hn::LoadU(d, row + width - n) > t) >> (n - rem);
    } else {
      std::uint8_t padded[64] = {};
      std::memcpy(padded, row + x + k, static_cast<size_t>(rem));
      tail = mask_bits(d, hn::LoadU(d, padded) > t) & ((std::uint64_t{1} << rem) - 1);
    }
    bits |= tail << k;
  }
  return bits;
}

}  // namespace

int find_runs(const std::uint8_t* row, int width, std::uint8_t threshold, Run* out) noexcept {
  // A row is read 64 pixels at a time into a word of foreground bits. A bit that differs from the
  // one before it (the pixel to the left, across words too) starts or ends a run; a word without
  // such an edge, which is most of a sparse frame, costs a compare per vector and no branch miss.
  const D8 d;
  const auto t = hn::Set(d, threshold);
  const int n = static_cast<int>(hn::Lanes(d));
  int count = 0;
  int start = 0;
  bool in_run = false;
  const auto emit = [&](std::uint64_t edges, int x) {
    while (edges != 0) {
      const int p = x + static_cast<int>(hwy::Num0BitsBelowLS1Bit_Nonzero64(edges));
      edges &= edges - 1;
      if (in_run) {
        out[count].xs = start;
        out[count].xe = p;
        ++count;
      } else {
        start = p;
      }
      in_run = !in_run;
    }
  };
  std::uint64_t left = 0;  // foreground bit of the pixel before the word
  int x = 0;
  for (; x + 64 <= width; x += 64) {
    // Background between blobs: 128 pixels whose maximum is not above T take one compare.
    while (left == 0 && x + 128 <= width) {
      auto hi = hn::LoadU(d, row + x);
      for (int k = n; k < 128; k += n) hi = hn::Max(hi, hn::LoadU(d, row + x + k));
      if (!hn::AllFalse(d, hi > t)) break;
      x += 128;
    }
    if (x + 64 > width) break;
    std::uint64_t fg = 0;
    for (int k = 0; k < 64; k += n) fg |= mask_bits(d, hn::LoadU(d, row + x + k) > t) << k;
    const std::uint64_t edges = fg ^ ((fg << 1) | left);
    left = fg >> 63;
    if (edges != 0) emit(edges, x);
  }
  if (x < width) {
    const int len = width - x;
    const std::uint64_t fg = foreground_word(d, row, width, x, len, t);
    emit((fg ^ ((fg << 1) | left)) & ((std::uint64_t{1} << len) - 1), x);
  }
  if (in_run) {
    out[count].xs = start;
    out[count].xe = width;
    ++count;
  }
  return count;
}

namespace {

#if HWY_TARGET != HWY_SCALAR
// The sum over a vector's lanes i of w[i] * i, as int32 lanes to be summed by the caller.
class OffsetWeigher {
 public:
  auto operator()(hn::VFromD<D8> v) const {
    auto sum1 = hn::Zero(d32_);
    auto sum0 = hn::ReorderWidenMulAccumulate(d32_, hn::BitCast(d16_, hn::ZipLower(du16_, v, zero_)), offset_lo_,
                                              hn::Zero(d32_), sum1);
    sum0 =
        hn::ReorderWidenMulAccumulate(d32_, hn::BitCast(d16_, hn::ZipUpper(du16_, v, zero_)), offset_hi_, sum0, sum1);
    return hn::RearrangeToOddPlusEven(sum0, sum1);
  }

 private:
  D8 d8_;
  hn::Repartition<std::uint16_t, D8> du16_;
  hn::Repartition<std::int16_t, D8> d16_;
  hn::Repartition<std::int32_t, D8> d32_;
  hn::VFromD<D8> zero_ = hn::Zero(d8_);
  // Each lane's offset, widened exactly as the weights are, so that the pairs line up whatever
  // order ZipLower/ZipUpper give the lanes on this target. madd (int16 pairs -> int32) is exact
  // since w * offset < 2^15.
  hn::VFromD<D8> iota_ = hn::Iota(d8_, 0);
  hn::VFromD<hn::Repartition<std::int16_t, D8>> offset_lo_ = hn::BitCast(d16_, hn::ZipLower(du16_, iota_, zero_));
  hn::VFromD<hn::Repartition<std::int16_t, D8>> offset_hi_ = hn::BitCast(d16_, hn::ZipUpper(du16_, iota_, zero_));
};

// Runs at least a vector long (the caller checks): whole vectors, widened and multiplied by their
// offsets.
WeightSums weight_sums_long(const std::uint8_t* w, int xs, int xe) noexcept {
  const D8 d8;
  const int n = static_cast<int>(hn::Lanes(d8));
  const std::uint8_t* p = w + xs;
  const int len = xe - xs;
  WeightSums out;
  const hn::Repartition<std::uint64_t, D8> d64;
  const hn::Repartition<std::int32_t, D8> d32;
  const OffsetWeigher weighted_offsets;
  // A block's int32 total stays below 2^31: 2048 chunks * 255 * (0 + 1 + ... + 63).
  constexpr int kBlockChunks = 2048;
  int i = 0;
  while (len - i >= n) {
    const int chunks = std::min((len - i) / n, kBlockChunks);
    auto sw = hn::Zero(d64);
    auto prefix = hn::Zero(d64);  // sum over chunks k of the weights of chunks 0..k
    auto local = hn::Zero(d32);
    for (int k = 0; k < chunks; ++k) {
      const auto v = hn::LoadU(d8, p + i + static_cast<std::ptrdiff_t>(k) * n);
      sw = hn::Add(sw, hn::SumsOf8(v));
      prefix = hn::Add(prefix, sw);
      local = hn::Add(local, weighted_offsets(v));
    }
    const auto s = static_cast<std::int64_t>(hn::GetLane(hn::SumOfLanes(d64, sw)));
    const auto pre = static_cast<std::int64_t>(hn::GetLane(hn::SumOfLanes(d64, prefix)));
    const std::int64_t off = hn::GetLane(hn::SumOfLanes(d32, local));
    // Pixel x = x0 + k * n + offset, and sum_k k * S_k = chunks * S - sum_k (S_0 + ... + S_k).
    const std::int64_t x0 = std::int64_t{xs} + i;
    out.sw += s;
    out.swx += x0 * s + std::int64_t{n} * (chunks * s - pre) + off;
    i += chunks * n;
  }
  if (i < len) {
    // The last full vector of the run, with the pixels already counted zeroed.
    const int rem = len - i;
    const auto v =
        hn::IfThenElseZero(hn::Not(hn::FirstN(d8, static_cast<size_t>(n - rem))), hn::LoadU(d8, p + len - n));
    const auto s = static_cast<std::int64_t>(hn::GetLane(hn::SumOfLanes(d64, hn::SumsOf8(v))));
    const std::int64_t off = hn::GetLane(hn::SumOfLanes(d32, weighted_offsets(v)));
    out.sw += s;
    out.swx += (std::int64_t{xe} - n) * s + off;
  }
  return out;
}
#endif

}  // namespace

WeightSums weight_sums(const std::uint8_t* row, int xs, int xe) noexcept {
  // A short run (a marble's row) is cheaper one pixel at a time than set up for vectors.
#if HWY_TARGET != HWY_SCALAR
  if (xe - xs >= std::max(32, static_cast<int>(hn::Lanes(D8())))) return weight_sums_long(row, xs, xe);
#endif
  WeightSums out;
  for (int x = xs; x < xe; ++x) {
    out.sw += row[x];
    out.swx += std::int64_t{row[x]} * x;
  }
  return out;
}

WeightSums weight_sums(const std::uint8_t* row, int width, int xs, int xe) noexcept {
#if HWY_TARGET != HWY_SCALAR
  const D8 d8;
  const int n = static_cast<int>(hn::Lanes(d8));
  if (xe - xs <= n && width >= n) {
    // One vector inside the row that covers the run, its other lanes zeroed: no loop whose exit
    // the branch predictor would have to guess for every run.
    const int base = std::min(xs, width - n);
    const auto active =
        hn::AndNot(hn::FirstN(d8, static_cast<size_t>(xs - base)), hn::FirstN(d8, static_cast<size_t>(xe - base)));
    const auto v = hn::IfThenElseZero(active, hn::LoadU(d8, row + base));
    const hn::Repartition<std::uint64_t, D8> d64;
    const hn::Repartition<std::int32_t, D8> d32;
    const auto sw = static_cast<std::int64_t>(hn::GetLane(hn::SumOfLanes(d64, hn::SumsOf8(v))));
    const std::int64_t off = hn::GetLane(hn::SumOfLanes(d32, OffsetWeigher{}(v)));
    return {sw, std::int64_t{base} * sw + off};
  }
#endif
  return weight_sums(row, xs, xe);
}

}  // namespace neopipe::kernels::detail
