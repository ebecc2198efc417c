#pragma once
// The table's texture: low-contrast procedural noise fixed to the world's coordinates (it moves
// with the scene in the onboard camera's view, not with the image). Value noise in two octaves:
// values hashed from the integer lattice points (so no tile repeats anywhere on the table),
// smoothstep between them; lattice `scale` and scale / 2 mm, weighted 2/3 and 1/3.

#include <cstdint>

namespace neopipe::sim {

class TableTexture {
 public:
  TableTexture(double scale_mm, std::uint64_t seed);
  /// The texture at world point (x, y) mm, in [-1, 1].
  [[nodiscard]] double operator()(double x, double y) const;

 private:
  [[nodiscard]] double octave(double x, double y, std::uint64_t seed) const;
  double inverse_scale_;
  std::uint64_t seed_;
};

}  // namespace neopipe::sim
