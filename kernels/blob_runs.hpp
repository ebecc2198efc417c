#pragma once
// The two per-pixel loops of blob extraction, kept apart from the labelling so that only this pair
// is written with Highway: finding the runs of a row and summing a run's weights. Internal to the
// kernels library.

#include <cstdint>

namespace neopipe::kernels::detail {

/// A maximal horizontal span [xs, xe) of foreground in one row, and its provisional label (a
/// union-find node), which find_runs leaves alone.
struct Run {
  int xs;
  int xe;
  int label;
};

/// Most runs find_runs can write for a row of `width` pixels: runs are separated by at least one
/// background pixel.
constexpr int max_runs(int width) {
  return width / 2 + 1;
}

/// Writes the runs of (row[x] > threshold), x in [0, width), left to right, to `out` (room for
/// max_runs(width)) and returns how many there are. Any width >= 1; `row` need not be aligned, and
/// nothing outside [row, row + width) is read.
int find_runs(const std::uint8_t* row, int width, std::uint8_t threshold, Run* out) noexcept;

/// Sums over a run of its weights w[x] and of w[x] * x.
struct WeightSums {
  std::int64_t sw = 0;
  std::int64_t swx = 0;
};

/// Sums over the run [xs, xe) of the row starting at `row`; reads only [xs, xe).
WeightSums weight_sums(const std::uint8_t* row, int xs, int xe) noexcept;

/// The same for a run of a row `width` pixels wide: reads only inside the row, but may read
/// outside the run, which makes a short run one masked vector.
WeightSums weight_sums(const std::uint8_t* row, int width, int xs, int xe) noexcept;

}  // namespace neopipe::kernels::detail
