#include "rig/seeds.hpp"

#include "sim/random.hpp"

namespace neopipe::rig {

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) {
  sim::Random r(seed ^ (0x9E3779B97F4A7C15ULL * (stream + 1)));
  return r.next();
}

std::uint64_t trial_seed(std::uint64_t seed, std::int64_t index) {
  sim::Random r(seed * 0x100000001B3ULL + static_cast<std::uint64_t>(index));
  return r.next();
}

}  // namespace neopipe::rig
