#include "sim/table_texture.hpp"

#include <cmath>

namespace neopipe::sim {
namespace {

// A lattice point's value in [-1, 1]: the SplitMix64 finaliser of its coordinates and the seed.
double lattice_value(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t z = seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL) ^
                    (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL);
  z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
  z ^= z >> 31U;
  return static_cast<double>(z >> 11U) * 0x1.0p-52 - 1.0;
}

double smoothstep(double t) {
  return t * t * (3 - 2 * t);
}

}  // namespace

TableTexture::TableTexture(double scale_mm, std::uint64_t seed)
    : inverse_scale_(1 / scale_mm), seed_(seed * 0x9E3779B97F4A7C15ULL + 0x7461626C65ULL) {}  // "table"

double TableTexture::octave(double x, double y, std::uint64_t seed) const {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx);
  const auto j = static_cast<std::int64_t>(fy);
  const double u = smoothstep(x - fx);
  const double v = smoothstep(y - fy);
  const double a = lattice_value(i, j, seed);
  const double b = lattice_value(i + 1, j, seed);
  const double c = lattice_value(i, j + 1, seed);
  const double d = lattice_value(i + 1, j + 1, seed);
  return (1 - v) * (a + u * (b - a)) + v * (c + u * (d - c));
}

double TableTexture::operator()(double x, double y) const {
  const double sx = x * inverse_scale_;
  const double sy = y * inverse_scale_;
  return (2 * octave(sx, sy, seed_) + octave(2 * sx, 2 * sy, seed_ + 1)) / 3;
}

}  // namespace neopipe::sim
