#pragma once
// The reliable, error-detectable and error-recoverable parkways (park-kender.md §3, §7): sub-graphs
// of the obvious and isolated parkways whose edges pass a reliability threshold or the QOC tests.
// They tell a user where in a world the navigator can travel safely, before any route is planned.

#include <vector>

#include "nav/mapmaker/parkways.hpp"
#include "nav/mapmaker/reliability.hpp"
#include "nav/mapmaker/verification.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

/// One parkway edge as the navigator would travel it: seek `description` at (from, corner).
struct ParkwayEdgeQuality {
  ParkwayEdge edge;
  Description description = Description::Isol;
  double reliability = 1;  ///< the step's: selection reliability times view agreement at `from`
  Verifiability verifiability = Verifiability::trivial;

  /// A mistake would show in the landmark's QOC (or none is possible).
  bool detectable() const { return verifiability != Verifiability::unverifiable; }
  /// Detectable, and every mistake can be led back by the recovery rules.
  bool recoverable() const {
    return verifiability == Verifiability::trivial || verifiability == Verifiability::correctable;
  }
};

/// Every edge of the obvious parkway (described Obvious) then of the isolated parkway (Isol), each
/// in the parkway's own order, with its reliability and verifiability.
std::vector<ParkwayEdgeQuality> parkway_edge_qualities(const WorldViews& views, const NavigatorErrors& errors);

struct ParkwaySubgraph {
  std::vector<ParkwayEdge> obvious;
  std::vector<ParkwayEdge> isolated;
};

struct QualifiedParkways {
  ParkwaySubgraph reliable;     ///< reliability >= the threshold
  ParkwaySubgraph detectable;   ///< error-detectable
  ParkwaySubgraph recoverable;  ///< error-recoverable
};

/// Splits the edges into the three sub-graphs; `reliable_threshold` in [0, 1].
QualifiedParkways qualify_parkways(const std::vector<ParkwayEdgeQuality>& edges, double reliable_threshold);

}  // namespace neopipe::nav::mapmaker
