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
std::uint64_t mask_bits(D8 d, M mask) {
  std::uint8_t bytes[8] = {};  // StoreMaskBits may write up to 8 bytes
  hn::StoreMaskBits(d, mask, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  return bits;
}

// Turns the foreground bits of consecutive chunks of a row into runs; a run may span chunks.
class RunEmitter {
 public:
  explicit RunEmitter(Run* out) : out_(out) {}

  bool in_run() const { return in_run_; }

  // Bit i of `fg` is pixel x + i; `valid` has a bit set for each pixel of the chunk, and fg has no
  // bits outside it.
  void chunk(std::uint64_t fg, std::uint64_t valid, int x) {
    // Inside a run the next event is a background pixel, outside it a foreground one. Flipping the
    // remaining bits after each event finds all of a chunk's edges with one count-trailing-zeros
    // each, however many runs it holds.
    std::uint64_t events = in_run_ ? ~fg & valid : fg;
    while (events != 0) {
      const int p = static_cast<int>(hwy::Num0BitsBelowLS1Bit_Nonzero64(events));
      if (in_run_) {
        out_[n_].xs = start_;
        out_[n_].xe = x + p;
        ++n_;
      } else {
        start_ = x + p;
      }
      in_run_ = !in_run_;
      events = ~events & valid & (~std::uint64_t{0} << p);
    }
  }

  int finish(int width) {
    if (in_run_) {
      out_[n_].xs = start_;
      out_[n_].xe = width;
      ++n_;
    }
    return n_;
  }

 private:
  Run* out_;
  int n_ = 0;
  int start_ = 0;
  bool in_run_ = false;
};

}  // namespace

int find_runs(const std::uint8_t* row, int width, std::uint8_t threshold, Run* out) noexcept {
  const D8 d;
  const int n = static_cast<int>(hn::Lanes(d));
  const std::uint64_t full = n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
  const auto t = hn::Set(d, threshold);
  RunEmitter runs(out);
  int x = 0;
  for (;;) {
    // Most of a frame is background and most of a large blob's row is foreground: test four
    // vectors at once (their max, or min, against T) and stop at the first block that changes.
    if (runs.in_run()) {
      while (x + 4 * n <= width) {
        const auto lo = hn::Min(hn::Min(hn::LoadU(d, row + x), hn::LoadU(d, row + x + n)),
                                hn::Min(hn::LoadU(d, row + x + 2 * n), hn::LoadU(d, row + x + 3 * n)));
        if (!hn::AllTrue(d, lo > t)) break;
        x += 4 * n;
      }
    } else {
      while (x + 4 * n <= width) {
        const auto hi = hn::Max(hn::Max(hn::LoadU(d, row + x), hn::LoadU(d, row + x + n)),
                                hn::Max(hn::LoadU(d, row + x + 2 * n), hn::LoadU(d, row + x + 3 * n)));
        if (!hn::AllFalse(d, hi > t)) break;
        x += 4 * n;
      }
    }
    if (x + n > width) break;
    const std::uint64_t fg = mask_bits(d, hn::LoadU(d, row + x) > t);
    if (fg != (runs.in_run() ? full : 0)) runs.chunk(fg, full, x);
    x += n;
  }
  if (x < width) {
    const int rem = width - x;
    std::uint64_t fg = 0;
    if (width >= n) {
      // The last full vector of the row overlaps pixels already seen; their bits are shifted out.
      fg = mask_bits(d, hn::LoadU(d, row + width - n) > t) >> (n - rem);
    } else {
      std::uint8_t padded[64] = {};
      std::memcpy(padded, row + x, static_cast<size_t>(rem));
      fg = mask_bits(d, hn::LoadU(d, padded) > t);
    }
    const std::uint64_t valid = (std::uint64_t{1} << rem) - 1;
    runs.chunk(fg & valid, valid, x);
  }
  return runs.finish(width);
}

namespace {

// Runs at least a vector long: whole vectors, widened and multiplied by their offsets.
WeightSums weight_sums_long(const std::uint8_t* w, int xs, int xe) noexcept {
  const D8 d8;
  const int n = static_cast<int>(hn::Lanes(d8));
  const std::uint8_t* p = w + xs;
  const int len = xe - xs;
  WeightSums out;
  if (len < n || HWY_TARGET == HWY_SCALAR) {
    for (int i = 0; i < len; ++i) {
      out.sw += p[i];
      out.swx += std::int64_t{p[i]} * (xs + i);
    }
    return out;
  }
#if HWY_TARGET != HWY_SCALAR
  const hn::Repartition<std::uint16_t, D8> du16;
  const hn::Repartition<std::int16_t, D8> d16;
  const hn::Repartition<std::int32_t, D8> d32;
  const hn::Repartition<std::uint64_t, D8> d64;
  const auto zero = hn::Zero(d8);
  // Each lane's offset in its chunk, widened exactly as the weights are, so that the pairs line up
  // whatever order ZipLower/ZipUpper give the lanes on this target.
  const auto iota = hn::Iota(d8, 0);
  const auto offset_lo = hn::BitCast(d16, hn::ZipLower(du16, iota, zero));
  const auto offset_hi = hn::BitCast(d16, hn::ZipUpper(du16, iota, zero));
  // sum of w * offset over one chunk; madd (int16 pairs -> int32) is exact since w * offset < 2^15.
  const auto weighted_offsets = [&](decltype(zero) v) {
    auto sum1 = hn::Zero(d32);
    auto sum0 = hn::ReorderWidenMulAccumulate(d32, hn::BitCast(d16, hn::ZipLower(du16, v, zero)), offset_lo,
                                              hn::Zero(d32), sum1);
    sum0 = hn::ReorderWidenMulAccumulate(d32, hn::BitCast(d16, hn::ZipUpper(du16, v, zero)), offset_hi, sum0, sum1);
    return hn::RearrangeToOddPlusEven(sum0, sum1);
  };
  // A block's int32 total stays below 2^31: 2048 chunks * 255 * (0 + 1 + ... + 63).
  constexpr int kBlockChunks = 2048;
  int i = 0;
  while (len - i >= n) {
    const int chunks = std::min((len - i) / n, kBlockChunks);
    auto sw = hn::Zero(d64);
    auto prefix = hn::Zero(d64);  // sum over chunks k of the weights of chunks 0..k
    auto local = hn::Zero(d32);
    for (int k = 0; k < chunks; ++k) {
      const auto v = hn::LoadU(d8, p + i + k * n);
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
#endif
  return out;
}

}  // namespace

WeightSums weight_sums(const std::uint8_t* row, int xs, int xe) noexcept {
  // A short run (a marble's row) is cheaper one pixel at a time than set up for vectors.
  if (xe - xs >= 32) return weight_sums_long(row, xs, xe);
  WeightSums out;
  for (int x = xs; x < xe; ++x) {
    out.sw += row[x];
    out.swx += std::int64_t{row[x]} * x;
  }
  return out;
}

}  // namespace neopipe::kernels::detail
