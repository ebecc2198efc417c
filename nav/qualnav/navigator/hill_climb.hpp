#pragma once
// The viewframe heading's hill-climb (qualnav.md §6, Decision): keep the goal landmarks in view and
// descend J = Σ (Ang_i,i+1 − goal_i)² over consecutive goal landmarks (in the goal viewframe's pan
// order), with the gradient from the range midpoints (∂β_i/∂P = n_i / r_i), in 5 mm steps; stall
// after 3 non-improving steps; done when every error is below 1°.

#include <Eigen/Core>
#include <optional>

#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

struct HillClimbSettings {
  double step_mm = 5;
  int stall_steps = 3;
  double done_error = 3.14159265358979323846 / 180;  ///< every |Ang error| below 1°
};

struct ClimbState {
  double cost = 0;                                     ///< J, rad²
  double worst_error = 0;                              ///< rad
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  ///< ∂J/∂P in `now`'s sensor frame, rad²/mm
  int pairs = 0;                                       ///< consecutive goal landmarks both in view
};

/// J, its gradient and the worst angle error of `now` against `goal` over the landmarks both see.
/// nullopt when fewer than two of the goal's landmarks are in view.
std::optional<ClimbState> climb_state(const Viewframe& now, const Viewframe& goal);

/// The step (sensor frame, mm) down the gradient, `settings.step_mm` long; zero for a flat J.
Eigen::Vector2d climb_step(const ClimbState& state, const HillClimbSettings& settings);

}  // namespace neopipe::nav::qualnav
