#pragma once
// Random scenes for the map tests: landmarks in a square, a camera somewhere, and what it measures
// of a triple from exact geometry (spec qrm.md §6), with its zero direction turned at random.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/measurement.hpp"
#include "nav/qrm/relational_map.hpp"

namespace neopipe::nav::qrm::scenes {

/// `n` points uniform in [0, 100]^2 with no degenerate triple in any order (redrawn until so).
inline std::vector<Eigen::Vector2d> random_landmarks(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0, 100);
  for (;;) {
    std::vector<Eigen::Vector2d> p;
    p.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
    if (!first_degenerate_triple(p)) return p;
  }
}

/// The sightings of a, b, c from `camera` with the camera's zero direction at `zero` (radians).
inline std::array<Sighting, 3> sightings(const Eigen::Vector2d& camera, double zero, const Eigen::Vector2d& a,
                                         const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  std::array<Sighting, 3> s;
  const std::array<Eigen::Vector2d, 3> p{a, b, c};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d v = p[i] - camera;
    s[i] = {std::atan2(v.y(), v.x()) - zero, v.norm()};
  }
  return s;
}

/// The first relation of `map` that lost the true state of its landmarks at `points`, as
/// "ij:k = {..} lost s"; empty when every relation holds its truth.
inline std::string first_lost_truth(const RelationalMap& map, const std::vector<Eigen::Vector2d>& points) {
  const auto& ids = map.landmarks();
  for (const LandmarkId i : ids) {
    for (const LandmarkId j : ids) {
      for (const LandmarkId k : ids) {
        if (i == j || j == k || i == k) continue;
        const State truth = classify(points[i], points[j], points[k]);
        if (!map.relation(i, j, k).contains(truth)) {
          std::ostringstream out;
          out << i << j << ':' << k << " = " << map.relation(i, j, k) << " lost " << truth;
          return out.str();
        }
      }
    }
  }
  return {};
}

}  // namespace neopipe::nav::qrm::scenes
