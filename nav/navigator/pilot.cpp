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

std::vector<Eigen::Vector2d> everything_seen(const Sighting& sighting) {
  std::vector<Eigen::Vector2d> all;
  all.reserve(sighting.objects.size() + sighting.partial.size());
  all.insert(all.end(), sighting.objects.begin(), sighting.objects.end());
  all.insert(all.end(), sighting.partial.begin(), sighting.partial.end());
  return all;
}

std::optional<std::size_t> nearest(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& predicted,
                                   double gate) {
  std::optional<std::size_t> best;
  double best_d2 = gate * gate;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - predicted).squaredNorm();
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

HeldView held_view(const Sighting& sighting, const Hold& hold, const WindowModel& window) {
  const Eigen::Vector2d offset = hold.landmark - window.corner_point(hold.corner);
  HeldView view;
  const std::vector<Eigen::Vector2d> all = everything_seen(sighting);
  const auto reference = nearest(all, hold.landmark, tracking_gate(0));
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Eigen::Vector2d exact = all[i] - offset;
    const bool inside = exact.x() > 0 && exact.x() < window.side && exact.y() > 0 && exact.y() < window.side;
    if (reference && i == *reference) {
      view.reference = view.points.size();
      view.points.push_back(all[i]);
    } else if (inside) {
      view.points.push_back(all[i]);
    }
  }
  if (!reference) {  // not seen (cannot happen right after an adjust): keep it where it was held
    view.reference = view.points.size();
    view.points.push_back(hold.landmark);
  }
  return view;
}

}  // namespace neopipe::nav::navigator::detail
