#include "nav/qrm/measurement.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "nav/qrm/branch_and_bound.hpp"
#include "nav/qrm/edc.hpp"
#include "nav/qrm/region_constraints.hpp"

namespace neopipe::nav::qrm {
namespace {

int order_sign(double first, double second, double tau) {
  if (first > second * (1 + tau)) return 1;
  if (second > first * (1 + tau)) return -1;
  return 0;
}

// sign * (later - earlier) > 0 as the constraint sign * (earlier - later) < 0.
void add_order(std::vector<Quadratic>& g, int sign, const Affine& later, const Affine& earlier) {
  if (sign == 0) return;
  g.emplace_back(2, std::vector<Product>{{static_cast<double>(sign), Affine::constant(1), earlier - later}});
}

}  // namespace

RangeOrder range_order(double range_a, double range_b, double range_c, double tau) {
  return {order_sign(range_b, range_a, tau), order_sign(range_c, range_a, tau), order_sign(range_c, range_b, tau)};
}

StateSet feasible_states(double bearing_a, double bearing_b, double bearing_c, const RangeOrder& order,
                         StateSet candidates, const MeasurementOptions& options) {
  if (!(options.rho > 1) || !std::isfinite(options.rho)) throw std::invalid_argument("measurement: rho must be > 1");
  if (candidates.empty()) return {};
  // Camera coordinates turned so that A's bearing is 0 and scaled so that A's range is 1; the unknowns
  // are x0 = r_B, x1 = r_C.
  const double beta = bearing_b - bearing_a;
  const double gamma = bearing_c - bearing_a;
  const AffinePoint a{Affine::constant(1), Affine::constant(0)};
  const AffinePoint b{Affine::unknown(0) * std::cos(beta), Affine::unknown(0) * std::sin(beta)};
  const AffinePoint c{Affine::unknown(1) * std::cos(gamma), Affine::unknown(1) * std::sin(gamma)};
  // Every state's problem is the order constraints and a sign of each of e1..e6: build the order
  // constraints, the six e_i and their negations once, and give the search each state's selection
  // (the same quadratics, bit for bit, as building them per state: negation flips product weights).
  std::vector<Quadratic> common;
  const Affine one = Affine::constant(1);
  add_order(common, order.b_vs_a, Affine::unknown(0), one);
  add_order(common, order.c_vs_a, Affine::unknown(1), one);
  add_order(common, order.c_vs_b, Affine::unknown(1), Affine::unknown(0));
  std::vector<Quadratic> common_negated;
  common_negated.reserve(common.size());
  for (const Quadratic& g : common) common_negated.push_back(g.negated());
  const std::array<Quadratic, 6> e = edc_quadratics(2, a, b, c);
  const std::array<Quadratic, 6> minus_e{e[0].negated(), e[1].negated(), e[2].negated(),
                                         e[3].negated(), e[4].negated(), e[5].negated()};
  std::vector<const Quadratic*> g(common.size() + 6);
  std::vector<const Quadratic*> minus_g(common.size() + 6);
  for (std::size_t j = 0; j < common.size(); ++j) {
    g[j] = &common[j];
    minus_g[j] = &common_negated[j];
  }
  Box box;
  box.lo = {1 / options.rho, 1 / options.rho, 0, 0};
  box.hi = {options.rho, options.rho, 0, 0};
  StateSet feasible;
  for (const State s : candidates) {
    // Sign +1 of e_i is the constraint -e_i < 0 (region_constraints' reading).
    const auto& signs = state_signs(s);
    for (std::size_t i = 0; i < 6; ++i) {
      g[common.size() + i] = signs[i] > 0 ? &minus_e[i] : &e[i];
      minus_g[common.size() + i] = signs[i] > 0 ? &e[i] : &minus_e[i];
    }
    if (find_feasible(g, minus_g, box, options.depth).witness) feasible.insert(s);
  }
  return feasible;
}

StateSet measure(const std::array<Sighting, 3>& abc, StateSet candidates, const MeasurementOptions& options) {
  for (const Sighting& s : abc) {
    if (!(s.range > 0) || !std::isfinite(s.range) || !std::isfinite(s.bearing)) {
      throw std::invalid_argument("measurement: ranges must be positive and finite, bearings finite");
    }
  }
  return feasible_states(abc[0].bearing, abc[1].bearing, abc[2].bearing,
                         range_order(abc[0].range, abc[1].range, abc[2].range, options.tau), candidates, options);
}

}  // namespace neopipe::nav::qrm
