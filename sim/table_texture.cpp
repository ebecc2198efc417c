#include "sim/table_texture.hpp"

namespace neopipe::sim {
namespace {

// A lattice point's value in [-1, 1): an integer hash of its coordinates and the seed
// (multiply-xorshift rounds, well mixed in every bit).
inline float lattice_value(std::int32_t i, std::int32_t j, std::uint32_t seed) {
  std::uint32_t h =
      (static_cast<std::uint32_t>(i) * 0x8DA6B343U) ^ (static_cast<std::uint32_t>(j) * 0xD8163841U) ^ seed;
  h ^= h >> 16U;
  h *= 0x7FEB352DU;
  h ^= h >> 15U;
  h *= 0x846CA68BU;
  h ^= h >> 16U;
  return static_cast<float>(h >> 8U) * (2.0F / 16777216.0F) - 1.0F;
}

// floor for the table's coordinates (far inside int32), written so the loop vectorises (GCC does
// not vectorise std::floor here).
inline std::int32_t floor_int(float v) {
  const auto t = static_cast<std::int32_t>(v);
  return t - (v < static_cast<float>(t) ? 1 : 0);
}

inline float octave(float x, float y, std::uint32_t seed) {
  const std::int32_t i = floor_int(x);
  const std::int32_t j = floor_int(y);
  const auto fx = static_cast<float>(i);
  const auto fy = static_cast<float>(j);
  const float tu = x - fx;
  const float tv = y - fy;
  const float u = tu * tu * (3 - 2 * tu);  // smoothstep
  const float v = tv * tv * (3 - 2 * tv);
  const float a = lattice_value(i, j, seed);
  const float b = lattice_value(i + 1, j, seed);
  const float c = lattice_value(i, j + 1, seed);
  const float d = lattice_value(i + 1, j + 1, seed);
  return (1 - v) * (a + u * (b - a)) + v * (c + u * (d - c));
}

inline float texture(float x, float y, float inverse_scale, std::uint32_t seed) {
  const float sx = x * inverse_scale;
  const float sy = y * inverse_scale;
  return (2 * octave(sx, sy, seed) + octave(2 * sx, 2 * sy, seed + 1)) * (1.0F / 3);
}

}  // namespace

TableTexture::TableTexture(double scale_mm, std::uint64_t seed)
    : inverse_scale_(static_cast<float>(1 / scale_mm)),
      seed_(static_cast<std::uint32_t>((seed * 0x9E3779B97F4A7C15ULL + 0x7461626C65ULL) >> 32U)) {}  // "table"

float TableTexture::operator()(float x, float y) const {
  return texture(x, y, inverse_scale_, seed_);
}

void TableTexture::evaluate(const float* x, const float* y, float* out, int n) const {
  const float s = inverse_scale_;
  const std::uint32_t seed = seed_;
  for (int i = 0; i < n; ++i) out[i] = texture(x[i], y[i], s, seed);
}

}  // namespace neopipe::sim
