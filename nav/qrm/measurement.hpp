#pragma once
// A measurement from an image (spec qrm.md §6): bearings in the camera frame (any zero direction,
// no compass) and a range order give, for a triple A, B, C, the states of AB:C that some ranges
// consistent with them produce, tested by branch and bound over the unknown ranges.

#include <array>

#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

struct MeasurementOptions {
  double rho = 100;  ///< the ranges of B and C relative to A's lie in [1/rho, rho] (spec §6 Decision)
  double tau = 0.1;  ///< two ranges are ordered only if their estimates differ by more than a factor 1 + tau
  int depth = 30;    ///< branch-and-bound depth (the paper's)
};

/// What is known of the order of the true ranges: the sign of r_B - r_A, r_C - r_A and r_C - r_B
/// (-1 or +1; 0 when the estimates are too close to tell).
struct RangeOrder {
  int b_vs_a = 0;
  int c_vs_a = 0;
  int c_vs_b = 0;
};

/// The order of three range estimates, omitting pairs within a factor 1 + tau.
RangeOrder range_order(double range_a, double range_b, double range_c, double tau);

/// The states s in `candidates` for which AB:C = s is feasible with A, B, C at the given bearings
/// (radians, counter-clockwise, any common zero) and the given range order.
StateSet feasible_states(double bearing_a, double bearing_b, double bearing_c, const RangeOrder& order,
                         StateSet candidates, const MeasurementOptions& options = {});

/// A landmark as the sensor sees it: bearing in the camera frame (radians) and a range estimate (any
/// unit: only ratios matter).
struct Sighting {
  double bearing = 0;
  double range = 1;
};

/// The measurement of AB:C from three sightings (A, B, C), testing only `candidates` (the states
/// still open in the map).
StateSet measure(const std::array<Sighting, 3>& abc, StateSet candidates, const MeasurementOptions& options = {});

}  // namespace neopipe::nav::qrm
