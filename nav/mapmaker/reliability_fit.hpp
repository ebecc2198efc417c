#pragma once
// The Monte Carlo simulations behind the step reliabilities (park-kender.md §6, Decision): perturb
// what the navigator measures by its errors, re-run its choice, count how often it still agrees with
// the error-free one. neopipe_reliability_fit fits the selection model to these estimates and checks
// the trajectory approximation against them; the tests re-run smaller versions.

#include <cstdint>
#include <span>

#include "nav/mapmaker/reliability.hpp"

namespace neopipe::nav::mapmaker {

struct SelectionSample {
  int visible = 0;            ///< objects in view, the reference included
  double relative_sigma = 0;  ///< sigma / a
  int trials = 0;
  int agreed = 0;  ///< trials in which the perturbed selection equalled the error-free one
  double reliability() const { return trials > 0 ? static_cast<double>(agreed) / trials : 0.0; }
};

/// `trials` random views: the reference held at SW of a unit window (margin 0.05), `visible` - 1
/// other objects uniform in the window at least 0.04 apart (marbles do not overlap); every position,
/// the reference's too, measured with per-axis error `relative_sigma`. Deterministic in `seed`.
SelectionSample simulate_selection(int visible, double relative_sigma, int trials, std::uint64_t seed);

struct SelectionFit {
  SelectionReliabilityModel model;
  double rms_error = 0;  ///< of the model against the samples' reliabilities
  double max_error = 0;
};

/// Weighted least squares of log(1/R - 1) = log k + beta log(n - 2) + gamma log s over the samples
/// whose estimate is neither 0 nor 1 (weights N R (1 - R), the inverse variance of the log odds);
/// the errors are over all samples. Throws std::invalid_argument with fewer than 3 usable samples.
SelectionFit fit_selection(std::span<const SelectionSample> samples);

/// Monte Carlo reliability of one trajectory: the reference measured with error e1 places the window
/// off by -e1, the direction is that of the measured landmark minus the measured reference, the
/// motion turns the heading by a normal angle of sd sqrt(t^2 + (r s / 2)^2) at the goal's distance s;
/// every other object lies off its surveyed place by its own error of the same sd; the first object
/// to enter the perturbed slide (exact geometry), not counting the reference and the direction
/// landmark, which the navigator knows, must be the goal.
double simulate_trajectory(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors,
                           int trials, std::uint64_t seed);

}  // namespace neopipe::nav::mapmaker
