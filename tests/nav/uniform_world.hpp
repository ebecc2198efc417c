#pragma once
// A world of n objects uniformly at random in a side x side square (overlaps allowed): the test
// worlds of the map-maker suites.

#include <random>

#include "nav/mapmaker/workspace.hpp"

namespace neopipe::nav::mapmaker::test_worlds {

inline Workspace uniform_world(int n, double side, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, side);
  Workspace w{{side, side}, {}};
  for (int i = 0; i < n; ++i) w.objects.emplace_back(u(rng), u(rng));
  return w;
}

}  // namespace neopipe::nav::mapmaker::test_worlds
