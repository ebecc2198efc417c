#include "nav/mapmaker/reliability.hpp"

#include <cmath>

// TEMPORARY stand-in so the map-maker links while branch nav-reliability fits the real function.
namespace neopipe::nav::mapmaker {

double selection_reliability(int visible, double sigma) {
  return visible <= 2 ? 1.0 : std::exp(-0.05 * sigma * (visible - 2));
}

double trajectory_reliability(const WorldViews&, const Trajectory&, const NavigatorErrors&) {
  return 0.9;
}

}  // namespace neopipe::nav::mapmaker
