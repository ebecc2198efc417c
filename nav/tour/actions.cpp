#include "nav/tour/actions.hpp"

#include <cmath>

namespace neopipe::nav::tour {

double wrap_turn_deg(double alpha_deg) {
  double w = std::fmod(alpha_deg, 360.0);
  if (w <= -180) w += 360;
  if (w > 180) w -= 360;
  return w;
}

TurnKind turn_kind(double alpha_deg, double tolerance_deg) {
  const double a = wrap_turn_deg(alpha_deg);
  if (std::abs(a) <= tolerance_deg) return TurnKind::none;
  if (180 - std::abs(a) <= tolerance_deg) return TurnKind::around;
  return a < 0 ? TurnKind::right : TurnKind::left;
}

bool same_action(const Action& a, const Action& b) {
  if (a.index() != b.index()) return false;
  if (const auto* t = std::get_if<Turn>(&a)) return t->alpha_deg == std::get<Turn>(b).alpha_deg;
  const auto& x = std::get<Travel>(a);
  const auto& y = std::get<Travel>(b);
  return x.distance == y.distance && x.dtheta_deg == y.dtheta_deg;
}

}  // namespace neopipe::nav::tour
