#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

const Sighting& Pilot::look() {
  sighting_ = eye_.look();
  ++report_.frames;
  if (observer_ != nullptr) observer_->frame_seen(eye_.last_frame(), sighting_);
  return sighting_;
}

const Sighting& Pilot::move_and_look(const Eigen::Vector2d& d) {
  // The navigator never turns on purpose: it has no compass to turn back by.
  arm_.move_relative(d.x(), d.y(), 0.0);
  report_.commanded_travel += d.norm();
  return look();
}

std::optional<std::size_t> nearest(const Sighting& sighting, const Eigen::Vector2d& predicted, double gate) {
  std::optional<std::size_t> best;
  double best_d2 = gate * gate;
  for (std::size_t i = 0; i < sighting.objects.size(); ++i) {
    const double d2 = (sighting.objects[i] - predicted).squaredNorm();
    if (d2 <= best_d2) {
      best = i;
      best_d2 = d2;
    }
  }
  return best;
}

double tracking_gate(double moved) {
  // The arm's error grows with the move (about 0.3 mm of sigma per 100 mm, plus the turn it makes
  // by error, which swings the far side of the window); marbles lie at least a diameter apart, so a
  // gate a few sigma wide cannot take a neighbour for the tracked object.
  return 1.5 + 0.05 * moved;
}

}  // namespace neopipe::nav::navigator::detail
