#pragma once
// One panorama fused into the map (spec qrm.md §6, §9): of the landmarks in view, the k nearest by
// range estimate; every triple of them, named in ascending id order (A < B < C), measured on the
// states of AB:C still open in the map and fused. What QRM's map building and its navigator share.

#include <cstddef>
#include <span>

#include "nav/qrm/measurement.hpp"
#include "nav/qrm/relational_map.hpp"

namespace neopipe::nav::qrm {

/// A landmark in one image: its identity, its bearing in the camera frame (radians,
/// counter-clockwise, any zero direction: no compass) and a range estimate (any unit: only the
/// order of ranges is used).
struct LandmarkSighting {
  LandmarkId id = 0;
  double bearing = 0;
  double range = 1;
};

struct ObservationOptions {
  std::size_t nearest = 18;  ///< k: only the k nearest landmarks by range estimate (spec §9 Decision)
  MeasurementOptions measurement;
};

/// What one image did to the map.
struct ObservationReport {
  std::size_t landmarks = 0;     ///< sightings used (at most k)
  std::size_t added = 0;         ///< of them, new to the map
  std::size_t triples = 0;       ///< triples measured
  std::size_t refined = 0;       ///< measurements that removed states
  std::size_t inconsistent = 0;  ///< measurements that contradicted the map (rolled back)
};

/// Fuses one image's sightings into `map`, adding the landmarks it has not seen yet. Throws
/// std::invalid_argument for a sighting seen twice or with a non-finite bearing or a range <= 0.
ObservationReport observe(RelationalMap& map, std::span<const LandmarkSighting> sightings,
                          const ObservationOptions& options = {});

}  // namespace neopipe::nav::qrm
