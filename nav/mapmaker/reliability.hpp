#pragma once
// Step reliabilities (park-kender.md §6): the probability that the navigator does what the map-maker
// predicts. Selecting the isolated landmark among n objects in view fails when position errors
// reorder the mutual neighbourhoods; a trajectory fails when direction errors let another object
// enter the sliding window first. Both are estimated by Monte Carlo (reliability_fit.hpp) and used
// here through a fitted function / an analytic approximation validated against it.

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

/// Probability that the navigator, seeing `visible` objects (the reference included) measured with
/// per-axis error `sigma`, picks the same isolated landmark as the error-free selection. 1 for
/// `visible` <= 2 (one candidate). The fitted function of docs/navigation.md.
double selection_reliability(int visible, double sigma);

/// Probability that the first object to enter the navigator's sliding window is `trajectory.to`,
/// given the errors of the two landmarks that define the direction and of the motion.
double trajectory_reliability(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors);

}  // namespace neopipe::nav::mapmaker
