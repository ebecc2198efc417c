#include "nav/qualnav/navigator/orientation_heading.hpp"

#include <cmath>

namespace neopipe::nav::qualnav {

std::optional<double> orientation_heading(OrientationKind kind, LandmarkId p, LandmarkId q, const Viewframe& view) {
  const ViewedLandmark* lp = view.find(p);
  if (lp == nullptr) return std::nullopt;
  if (kind == OrientationKind::a) return lp->bearing;
  const ViewedLandmark* lq = view.find(q);
  if (lq == nullptr) return std::nullopt;
  // The signed angle from P to Q: turning away from Q at P is turning the other way.
  const double p_to_q = angle_between(*lp, *lq);
  switch (kind) {
    case OrientationKind::b:
      return wrap_angle(lp->bearing + p_to_q / 2);
    case OrientationKind::l:
      return wrap_angle(lp->bearing - std::copysign(kOrientationTurn, p_to_q));
    case OrientationKind::r:
      return wrap_angle(lq->bearing + std::copysign(kOrientationTurn, p_to_q));
    case OrientationKind::a:
      break;
  }
  return lp->bearing;
}

}  // namespace neopipe::nav::qualnav
