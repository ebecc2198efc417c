#pragma once
// The table's texture: low-contrast procedural noise fixed to the world's coordinates (it moves
// with the scene in the onboard camera's view, not with the image). Value noise in two octaves:
// values hashed from the integer lattice points (so no tile repeats anywhere on the table),
// smoothstep between them; lattice `scale` and scale / 2 mm, weighted 2/3 and 1/3. In float with
// a 32-bit hash, so rows of points vectorise.

#include <cstdint>

namespace neopipe::sim {

class TableTexture {
 public:
  TableTexture(double scale_mm, std::uint64_t seed);
  /// The texture at world point (x, y) mm, in [-1, 1].
  [[nodiscard]] float operator()(float x, float y) const;
  /// The same at `n` points (world mm) into `out`.
  void evaluate(const float* x, const float* y, float* out, int n) const;

 private:
  float inverse_scale_;
  std::uint32_t seed_;
};

}  // namespace neopipe::sim
