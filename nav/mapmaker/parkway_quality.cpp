#include "nav/mapmaker/parkway_quality.hpp"

#include <fmt/format.h>

#include <cmath>

#include "nav/mapmaker/view_agreement.hpp"

namespace neopipe::nav::mapmaker {

std::vector<ParkwayEdgeQuality> parkway_edge_qualities(const WorldViews& views, const NavigatorErrors& errors) {
  std::vector<ParkwayEdgeQuality> out;
  const auto add = [&](const std::vector<ParkwayEdge>& edges, Description description) {
    for (const ParkwayEdge& e : edges) {
      const Placement from{e.from, e.corner};
      const int visible = static_cast<int>(views.visible(from).size());
      const auto confusable = confusable_in_view(views, from, e.to, description);
      const double reliability = selection_reliability(visible, errors.sigma, views.window().side) *
                                 view_agreement(views, from, description, errors.sigma);
      out.push_back({e, description, reliability, check_step(views, e.to, confusable).kind});
    }
  };
  add(obvious_parkway(views), Description::Obvious);
  add(isolated_parkway(views), Description::Isol);
  return out;
}

QualifiedParkways qualify_parkways(const std::vector<ParkwayEdgeQuality>& edges, double reliable_threshold) {
  if (!(reliable_threshold >= 0 && reliable_threshold <= 1)) {
    throw MapError(fmt::format("reliable threshold {}: expected a probability in [0, 1]", reliable_threshold));
  }
  QualifiedParkways q;
  for (const ParkwayEdgeQuality& e : edges) {
    const auto pick = [&](ParkwaySubgraph& g) {
      (e.description == Description::Obvious ? g.obvious : g.isolated).push_back(e.edge);
    };
    if (e.reliability >= reliable_threshold) pick(q.reliable);
    if (e.detectable()) pick(q.detectable);
    if (e.recoverable()) pick(q.recoverable);
  }
  return q;
}

}  // namespace neopipe::nav::mapmaker
