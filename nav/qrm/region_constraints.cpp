#include "nav/qrm/region_constraints.hpp"

#include "nav/qrm/edc.hpp"

namespace neopipe::nav::qrm {

std::array<Quadratic, 6> edc_quadratics(int unknowns, const AffinePoint& p, const AffinePoint& q,
                                        const AffinePoint& r) {
  const Affine qpx = q.x - p.x;
  const Affine qpy = q.y - p.y;
  const Affine rpx = r.x - p.x;
  const Affine rpy = r.y - p.y;
  const Affine rqx = r.x - q.x;
  const Affine rqy = r.y - q.y;
  const auto sq = [](double w, const Affine& f) { return Product{w, f, f}; };
  return {
      Quadratic(unknowns, {{1, qpx, rpy}, {-1, qpy, rpx}}),                     // left of P->Q
      Quadratic(unknowns, {{1, qpx, rpx}, {1, qpy, rpy}}),                      // in front of P
      Quadratic(unknowns, {{1, qpx, rqx}, {1, qpy, rqy}}),                      // beyond Q
      Quadratic(unknowns, {sq(1, rqx), sq(1, rqy), sq(-1, rpx), sq(-1, rpy)}),  // closer to P
      Quadratic(unknowns, {sq(1, rpx), sq(1, rpy), sq(-1, qpx), sq(-1, qpy)}),  // far from P
      Quadratic(unknowns, {sq(1, rqx), sq(1, rqy), sq(-1, qpx), sq(-1, qpy)}),  // far from Q
  };
}

std::vector<Quadratic> region_constraints(int unknowns, const AffinePoint& p, const AffinePoint& q,
                                          const AffinePoint& r, State s) {
  const std::array<Quadratic, 6> e = edc_quadratics(unknowns, p, q, r);
  const auto& signs = state_signs(s);
  std::vector<Quadratic> constraints;
  constraints.reserve(6);
  for (int i = 0; i < 6; ++i) constraints.push_back(signs[i] > 0 ? e[i].negated() : e[i]);
  return constraints;
}

}  // namespace neopipe::nav::qrm
