#pragma once
// The strict inequalities that say "PQ:R is in region s" when the points' coordinates are affine in
// the unknowns of a branch-and-bound problem (composition: C and D unknown; measurement: the ranges).

#include <array>
#include <vector>

#include "nav/qrm/quadratic.hpp"
#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

struct AffinePoint {
  Affine x;
  Affine y;
};

/// e1..e6 of spec §2 for (p, q, r) as quadratics in `unknowns` unknowns, grouped as products of
/// coordinate differences (so |QR|^2 is a sum of exact squares in the interval bound).
std::array<Quadratic, 6> edc_quadratics(int unknowns, const AffinePoint& p, const AffinePoint& q, const AffinePoint& r);

/// The six constraints g < 0 equivalent to PQ:R = s (each sign of state_signs(s) as -sign * e_i < 0).
std::vector<Quadratic> region_constraints(int unknowns, const AffinePoint& p, const AffinePoint& q,
                                          const AffinePoint& r, State s);

}  // namespace neopipe::nav::qrm
