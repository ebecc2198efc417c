#pragma once
// Sensor noise fast enough for thousands of frames per second: a table of exact N(0, 1) samples
// (Box-Muller from the seeded generator) read at a random offset per image row. Every pixel is
// Gaussian; neighbouring pixels are independent; rows of a frame start at independent offsets.

#include <cstdint>
#include <span>
#include <vector>

#include "sim/random.hpp"

namespace neopipe::sim {

class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed);
  /// `length` samples for one row (length <= kRowMax), from `row_rng`'s next offset.
  [[nodiscard]] std::span<const float> row(Random& row_rng, int length) const;

  static constexpr int kRowMax = 8192;

 private:
  std::vector<float> table_;
};

/// The generator of frame `index`'s row offsets: same (seed, index) -> same noise.
Random frame_random(std::uint64_t seed, std::int64_t index);

}  // namespace neopipe::sim
