#include "nav/navigator/pilot.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace neopipe::nav::navigator::detail {

const Sighting& Pilot::look() {
  sighting_ = eye_.look();
  ++report_.frames;
  if (observer_ != nullptr) observer_->frame_seen(eye_.last_frame(), sighting_);
  return sighting_;
}

const Sighting& Pilot::move_and_look(const Eigen::Vector2d& d) {
  // The navigator never turns on purpose: it corrects for the turns the arm makes by error in what
  // it concludes from its views (held_view), not by turning back.
  moved_ = arm_.move_relative(d.x(), d.y(), 0.0);
  report_.commanded_travel += d.norm();
  const std::vector<Eigen::Vector2d> before = sighting_.objects;
  look();
  if (!moved_) return sighting_;
  odometry_ += Eigen::Rotation2Dd(heading_) * d;
  if (!config_.track_heading) return sighting_;
  // The turn since the last look: the rotation that best takes the objects' predicted places to
  // where they are seen (least squares about their centroids; the translation error drops out).
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pairs;
  const double gate = tracking_gate(d.norm());
  // Marbles whose centre lies near the border show a small cap, located less well: a lot for an angle.
  const double clear = 0.5;
  const double side = config_.window.side;
  const auto whole = [&](const Eigen::Vector2d& p) { return p.minCoeff() > clear && p.maxCoeff() < side - clear; };
  for (const Eigen::Vector2d& p : before) {
    if (!whole(p)) continue;
    const auto i = nearest(sighting_.objects, p - d, gate);
    if (i && whole(sighting_.objects[*i])) pairs.emplace_back(p - d, sighting_.objects[*i]);
  }
  if (pairs.size() < 2) return sighting_;
  Eigen::Vector2d mean_predicted = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_seen = Eigen::Vector2d::Zero();
  for (const auto& [predicted, seen] : pairs) {
    mean_predicted += predicted;
    mean_seen += seen;
  }
  mean_predicted /= static_cast<double>(pairs.size());
  mean_seen /= static_cast<double>(pairs.size());
  double cross = 0;
  double dot = 0;
  double spread = 0;
  for (const auto& [predicted, seen] : pairs) {
    const Eigen::Vector2d a = predicted - mean_predicted;
    const Eigen::Vector2d b = seen - mean_seen;
    cross += a.x() * b.y() - a.y() * b.x();
    dot += a.dot(b);
    spread += a.squaredNorm();
  }
  if (spread <= 0) return sighting_;
  // Objects close together measure the turn poorly. Weigh the measurement against what a move of
  // this length is expected to turn (least-squares angle variance: 2 sigma^2 / spread), so that
  // many short moves do not pile up measurement noise.
  const double expected = config_.turn_sigma0 + config_.turn_sigma_per_mm * d.norm();
  const double noise = 2 * config_.position_sigma * config_.position_sigma / spread;
  const double weight = expected * expected / (expected * expected + noise);
  // Seen objects turned by -delta when the window turned by delta.
  heading_ -= weight * std::atan2(cross, dot);
  return sighting_;
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

HeldView held_view(const Sighting& sighting, const Hold& hold, const WindowModel& window, double heading,
                   double margin) {
  // The exact window: axis-aligned as the map-maker's (the window's turn undone), the landmark at
  // its corner.
  const Eigen::Rotation2Dd unturn(heading);
  const Eigen::Vector2d corner = window.corner_point(hold.corner);
  HeldView view;
  const std::vector<Eigen::Vector2d> all = everything_seen(sighting);
  const auto reference = nearest(all, hold.landmark, tracking_gate(0));
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Eigen::Vector2d exact = corner + unturn * (all[i] - hold.landmark);
    const double depth = std::min({exact.x(), exact.y(), window.side - exact.x(), window.side - exact.y()});
    if (reference && i == *reference) {
      view.reference = view.points.size();
      view.points.push_back(all[i]);
      view.depth.push_back(depth);
    } else if (depth > 0) {
      view.points.push_back(all[i]);
      view.depth.push_back(depth);
    } else if (depth > -margin) {
      view.just_outside.push_back(all[i]);
      view.outside_depth.push_back(depth);
    }
  }
  if (!reference) {  // not seen (cannot happen right after an adjust): keep it where it was held
    view.reference = view.points.size();
    view.points.push_back(hold.landmark);
    view.depth.push_back(window.margin);
  }
  return view;
}

}  // namespace neopipe::nav::navigator::detail
