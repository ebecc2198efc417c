#pragma once
// Step reliabilities (park-kender.md §6): the probability that the navigator does what the map-maker
// predicts. Selecting the isolated landmark among n objects in view fails when position errors
// reorder the mutual neighbourhoods; a trajectory fails when direction and motion errors let another
// object enter the sliding window first, or let the goal slip past it. The first is a function
// fitted to Monte Carlo estimates, the second an analytic approximation; reliability_fit.hpp holds
// the simulations both are checked against (docs/navigation.md, "Reliability").

#include <numbers>

#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

/// The navigator's error model as the map-maker sees it.
struct NavigatorErrors {
  /// Per-axis standard deviation of the positions the navigator measures in its window, mm (the
  /// map-maker's own position error comes from the calibration report and adds to it).
  double sigma = 1.0;
  /// Across-track translation error of a move: sd in mm per mm moved.
  double translation_per_mm = 0.003;
  /// Heading error of a move: sd in rad per mm moved.
  double rotation_per_mm = 0.002 * std::numbers::pi / 180;
};

/// The fitted selection reliability R(n, s) = 1 / (1 + k (n - 2)^beta s^gamma), s = sigma / a:
/// 1 / R - 1 is the odds of a wrong pick, which the Monte Carlo estimates show growing as a power of
/// the number of rivals n - 2 and of the relative position error.
struct SelectionReliabilityModel {
  double log_k = 0;
  double beta = 0;
  double gamma = 0;
  double operator()(int visible, double relative_sigma) const;
};

/// The coefficients fitted by neopipe_reliability_fit and published in docs/navigation.md.
SelectionReliabilityModel fitted_selection_model();

/// Probability that the navigator, seeing `visible` objects (the reference included) measured with
/// per-axis error `sigma` in a window of side `window_side`, picks the same isolated landmark as the
/// error-free selection. 1 for `visible` <= 2 (one candidate) or sigma 0.
double selection_reliability(int visible, double sigma, double window_side);

/// Probability that the first object to enter the navigator's sliding window is `trajectory.to`.
///
/// The approximation: the slide's lateral offset at distance s is sd(s) Z with one standard normal Z
/// (the heading error dominates, and it moves the whole path one way), where
///   sd(s)^2 = sigma^2 + s^2 (2 sigma^2 / L^2 + t^2) + (r s^2 / 2)^2,
/// L the baseline between the two landmarks, t and r the motion errors per mm. The goal is reached
/// while the offset keeps it inside the swept band and keeps every object beside the band out of it
/// up to the goal's entry; each such object bounds Z on its side, so R = Phi(z_hi) - Phi(z_lo).
double trajectory_reliability(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors);

}  // namespace neopipe::nav::mapmaker
