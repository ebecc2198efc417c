#pragma once
// Where each marble is in an image: (u, v) where its centre projects (at height d / 2 for a sphere,
// on the table for a flat disk) and (u0, v0) where its contact point with the table projects. Their
// difference is the parallax a survey must remove: a sphere's outline is centred on (u, v), but the
// workspace position the map wants is under it, at (u0, v0).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "sim/camera.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

struct MarbleTruth {
  int id = 0;
  double u = 0;  ///< the centre's projection (px)
  double v = 0;
  double u0 = 0;  ///< the contact point's (px)
  double v0 = 0;
};

/// The marbles whose centres project strictly inside the image, in id order. `shape` says where the
/// centre is: sphere (d / 2 up) or disk (on the table: then (u, v) = (u0, v0)).
std::vector<MarbleTruth> marble_truth(std::span<const Eigen::Vector2d> centres, double diameter,
                                      const PinholeCamera& camera, MarbleShape shape = MarbleShape::sphere);

}  // namespace neopipe::sim
