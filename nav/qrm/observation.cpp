#include "nav/qrm/observation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace neopipe::nav::qrm {

ObservationReport observe(RelationalMap& map, std::span<const LandmarkSighting> sightings,
                          const ObservationOptions& options) {
  std::vector<LandmarkSighting> used(sightings.begin(), sightings.end());
  for (const LandmarkSighting& s : used) {
    if (!std::isfinite(s.bearing) || !(s.range > 0) || !std::isfinite(s.range)) {
      throw std::invalid_argument("observation: landmark " + std::to_string(s.id) +
                                  " has a non-finite bearing or a range that is not positive");
    }
  }
  // Nearest first; equal estimates by id, so the choice of the k does not depend on input order.
  std::sort(used.begin(), used.end(), [](const LandmarkSighting& a, const LandmarkSighting& b) {
    return a.range != b.range ? a.range < b.range : a.id < b.id;
  });
  if (used.size() > options.nearest) used.resize(options.nearest);
  std::sort(used.begin(), used.end(), [](const LandmarkSighting& a, const LandmarkSighting& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < used.size(); ++i) {
    if (used[i].id == used[i - 1].id) {
      throw std::invalid_argument("observation: landmark " + std::to_string(used[i].id) + " is seen twice");
    }
  }

  ObservationReport report;
  report.landmarks = used.size();
  for (const LandmarkSighting& s : used) {
    if (!map.has_landmark(s.id)) {
      map.add_landmark(s.id);
      ++report.added;
    }
  }
  const auto as_sighting = [](const LandmarkSighting& s) { return Sighting{s.bearing, s.range}; };
  for (std::size_t i = 0; i < used.size(); ++i) {
    for (std::size_t j = i + 1; j < used.size(); ++j) {
      for (std::size_t k = j + 1; k < used.size(); ++k) {
        const LandmarkSighting& a = used[i];
        const LandmarkSighting& b = used[j];
        const LandmarkSighting& c = used[k];
        const StateSet open = map.relation(a.id, b.id, c.id);
        ++report.triples;
        const StateSet measured =
            measure(std::array{as_sighting(a), as_sighting(b), as_sighting(c)}, open, options.measurement);
        switch (map.fuse(a.id, b.id, c.id, measured)) {
          case FuseOutcome::unchanged:
            break;
          case FuseOutcome::refined:
            ++report.refined;
            break;
          case FuseOutcome::inconsistent:
            ++report.inconsistent;
            break;
        }
      }
    }
  }
  return report;
}

}  // namespace neopipe::nav::qrm
