#pragma once
// Whether the navigator sees the view the map-maker predicts (park-kender.md §6): an object near an
// edge of the window may be in view for one and out of view for the other, since both place the
// window from positions known only to within sigma. When that flip changes what the entry's
// description selects (or leaves an Obvious entry with two candidates), the step goes wrong before
// any selection error. Multiplied into every step's reliability, it steers the reliability-aware
// paths away from such borderline placements.

#include "nav/common/landmarks.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

/// Probability that no object near the window's edges at `from` crosses them in a way that changes
/// the landmark `description` selects there. Each object's offset from the reference is off by
/// N(0, 2 sigma^2) per axis (both positions carry the error); an object flips when its nearest edge
/// moves past it; the flips are taken as independent. 1 when sigma is 0.
double view_agreement(const WorldViews& views, const Placement& from, Description description, double sigma);

/// Probability that the navigator, judging which object entered its sliding window first from its
/// own measurements of them (each off by sigma per axis), agrees that the trajectory's goal did. Only
/// objects entering by the goal's edge soon after it matter: for them no error of the slide changes
/// the order (trajectory_reliability), but one depth * rate deeper beyond the edge is taken for the
/// first with probability Phi(-depth / (sqrt 2 sigma)). Independent, as view_agreement's flips.
double entry_order_agreement(const WorldViews& views, const Trajectory& trajectory, double sigma);

}  // namespace neopipe::nav::mapmaker
