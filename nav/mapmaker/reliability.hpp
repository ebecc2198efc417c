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

/// The share of a step's mistakes the navigator catches and undoes before they cost the journey:
/// its map's QOC rules, the next candidate when a later entry leads nowhere, the views its margin
/// explains (nav/navigator/follow.cpp). A step rated R on its first try is forecast to cost the
/// journey nothing with 1 - (1 - share) (1 - R). One share for every kind of step: fitted to the
/// rig's Monte Carlo of the real navigator; shares per kind differ from one half of the surveys to
/// the other more than between kinds (docs/navigation.md, "Recovery credit"). 0 for a navigator that
/// does not recover.
struct RecoveryCredit {
  double share = 0;
  /// The published fit (scripts/fit_recovery_credit.py; docs/navigation.md).
  static RecoveryCredit fitted();
  double rated(double first_try) const { return 1 - (1 - share) * (1 - first_try); }
};

/// The navigator's error model as the map-maker sees it.
struct NavigatorErrors {
  /// Per-axis standard deviation of the positions the navigator measures in its window, mm (the
  /// map-maker's own position error comes from the calibration report and adds to it).
  double sigma = 1.0;
  /// Across-track translation error of a move: sd in mm per mm moved.
  double translation_per_mm = 0.003;
  /// Heading error of a move: sd in rad per mm moved.
  double rotation_per_mm = 0.002 * std::numbers::pi / 180;
  /// What the navigator recovers from (none by default: each step's first try is its rating).
  RecoveryCredit recovery;
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

/// Probability that the navigator, measuring the view at `from` with per-axis error `sigma`, takes
/// the same farthest (Description::Far) or nearest (Near) object as the map-maker. The landmark must
/// stay in view, and no other object may both be in view and beat it: the difference of two
/// distances d_t - d_j is off by u_t.(e_t - e_r) - u_j.(e_j - e_r), u the unit vectors from the
/// reference, and an object just outside the window that may come into view counts as a rival (a
/// joint event view_agreement, which judges flips on the map-maker's positions, cannot see). The
/// reference's error e_r, shared by every rival, is integrated over; given it, the rivals are
/// independent. Agrees with the Monte Carlo to 0.01 (tests/nav/test_reliability.cpp). 1 with nothing
/// selected or sigma 0. Includes the view's agreement for these descriptions.
double distance_rank_reliability(const WorldViews& views, const Placement& from, Description description, double sigma);

/// Probability that the first object to enter the navigator's sliding window is `trajectory.to`.
///
/// The approximation: across the track the slide is off by d(s) = e c(s) + s g at distance s, with
/// e ~ N(0, sigma^2) the reference's survey error (it places the window and turns the direction:
/// c(s) = 1 - s / L on Trajp, 1 + s / L on Trajn, over the baseline L) and
/// g ~ N(0, sigma^2 / L^2 + t^2 + (r s_g / 2)^2) the landmark's error plus the motion's across-track
/// (t) and heading (r) errors over the slide s_g.
/// Success needs the goal to stay inside the swept band, no object beside the band to be swept
/// before the goal, and no object in the band to overtake it; each is a bound on d at some s. R
/// integrates the bounds over g (64-node quadrature) with e's interval in closed form, times the
/// chance that the start view agrees (the goal not already in view, no view object pushed ahead of
/// a leading edge). Checked against simulate_trajectory in docs/navigation.md.
double trajectory_reliability(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors);

}  // namespace neopipe::nav::mapmaker
