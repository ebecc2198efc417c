#include "sim/gaussian_noise.hpp"

namespace neopipe::sim {
namespace {
// 2^18 samples: 1 MiB, stays in L2; offsets are drawn uniformly, so a row repeats another's samples
// only by a 1-in-2^18 coincidence.
constexpr std::size_t kTableSize = std::size_t{1} << 18U;
}  // namespace

GaussianNoise::GaussianNoise(std::uint64_t seed) : table_(kTableSize + kRowMax) {
  Random rng(seed ^ 0x6E6F697365ULL);  // "noise": keep it apart from other uses of the same seed
  for (auto& v : table_) v = static_cast<float>(rng.normal());
}

std::span<const float> GaussianNoise::row(Random& row_rng, int length) const {
  const auto offset = static_cast<std::size_t>(row_rng.next() % kTableSize);
  return {table_.data() + offset, static_cast<std::size_t>(length)};
}

Random frame_random(std::uint64_t seed, std::int64_t index) {
  return Random(seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(index) + 1);
}

}  // namespace neopipe::sim
