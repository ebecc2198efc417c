#pragma once
// How a camera turns the scene into gray levels: flat dark workspace, bright shaded marbles,
// illumination gradient, blur, Gaussian noise. Each effect can be switched off (0).

#include <cstdint>

namespace neopipe::sim {

struct ImageModel {
  double background = 40;  ///< gray level of the bare workspace
  double marble = 210;     ///< gray level at a marble's centre
  /// Brightness at the rim as a fraction of the centre's excess over the background: a marble is a
  /// shaded dome (sqrt(1 - r^2) profile) that stays clearly brighter than the workspace to its edge.
  double rim = 0.45;
  double gradient = 0.15;          ///< illumination varies by +-this fraction across the image (0: uniform)
  double gradient_angle_deg = 30;  ///< direction of increasing light, in image axes
  double blur_sigma = 0.7;         ///< px, Gaussian optical blur (0: sharp)
  double noise_sigma = 2.0;        ///< gray levels, additive Gaussian sensor noise (0: none)
  std::uint64_t seed = 1;          ///< noise seed; a frame's noise depends on this and the frame's index
};

}  // namespace neopipe::sim
