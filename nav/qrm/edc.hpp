#pragma once
// The extended double cross (spec qrm.md §2): where C lies relative to the directed segment A->B,
// one of 20 open regions cut by six signs, and which regions touch (metric M4).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

/// e1..e6 of spec §2, in units of length squared: C left of A->B, in front of A, beyond B, closer to A
/// than to B, far from A, far from B (each "true" when > 0).
std::array<double, 6> edc_values(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// A point this close (relative to |AB|^2) to a region boundary is degenerate (spec §2).
inline constexpr double kDegenerateTolerance = 1e-9;

/// The state of AB:C, or 0 when some |e_i| <= 1e-9 |AB|^2 (C on a boundary, or A = B).
State classify(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// The first degenerate triple (i < j < k) of `points` (classify() is 0 for one of its six orders),
/// or none. The simulator resamples such worlds; a user's world file holding one is an error.
std::optional<std::array<std::size_t, 3>> first_degenerate_triple(std::span<const Eigen::Vector2d> points);

/// The signs (+1, -1) of e1..e6 everywhere inside region `s` (1..20): the strict inequalities that
/// define it, used by the composition and measurement problems.
const std::array<std::int8_t, 6>& state_signs(State s);

/// Spec §2's sample point of region `s` for A = (0,0), B = (0,1).
Eigen::Vector2d sample_point(State s);

/// The regions whose closures touch region `s`'s closure along an edge or at a vertex (spec §2).
StateSet adjacent(State s);

/// Reflection across line AB: the other state of spec §2's row (1 <-> 2, 5 <-> 10, ...).
State mirror(State s);

/// The RNG lune {7, 8, 13, 14}: C nearer to both A and B than they are to each other.
inline constexpr StateSet kLune{7, 8, 13, 14};

}  // namespace neopipe::nav::qrm
