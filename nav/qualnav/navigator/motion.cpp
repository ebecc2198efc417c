#include "nav/qualnav/navigator/motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace neopipe::nav::qualnav {
namespace {

using Eigen::Vector2d;

double point_segment_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

Vector2d unit(double bearing) {
  return {std::cos(bearing), std::sin(bearing)};
}

}  // namespace

double track_gap(const ViewedLandmark& l, const Vector2d& end) {
  const Vector2d a = l.range_lo * unit(l.bearing);
  const Vector2d b = l.range_hi * unit(l.bearing);
  // Distance between two segments in the plane: they do not cross when the landmark is not on the
  // track (a crossing gives 0 from the endpoint tests below only approximately, so sample too).
  double gap =
      std::min({point_segment_distance(Vector2d::Zero(), a, b), point_segment_distance(end, a, b),
                point_segment_distance(a, Vector2d::Zero(), end), point_segment_distance(b, Vector2d::Zero(), end)});
  const double cross_ab = (b - a).x() * end.y() - (b - a).y() * end.x();
  if (std::abs(cross_ab) > 1e-12) {
    // Proper intersection of origin→end with a→b.
    const Vector2d& d = a;
    const double t = (d.x() * (b - a).y() - d.y() * (b - a).x()) / (end.x() * (b - a).y() - end.y() * (b - a).x());
    const double u = (d.x() * end.y() - d.y() * end.x()) / (end.x() * (b - a).y() - end.y() * (b - a).x());
    if (t >= 0 && t <= 1 && u >= 0 && u <= 1) gap = 0;
  }
  return gap;
}

double current_gap(const ViewedLandmark& l) {
  return l.range_lo;
}

std::optional<Vector2d> safe_move(const Viewframe& view, double bearing, double length, const ClearanceRule& rule,
                                  std::optional<LandmarkId> ignore) {
  constexpr double kTurn = 15 * std::numbers::pi / 180;
  for (const double scale : {1.0, 0.5}) {
    for (int k = 0; k <= 12; ++k) {
      for (const int sign : {1, -1}) {
        if ((k == 0 || k == 12) && sign < 0) continue;
        const Vector2d end = scale * length * unit(bearing + sign * k * kTurn);
        const bool safe = std::all_of(view.landmarks.begin(), view.landmarks.end(), [&](const ViewedLandmark& l) {
          if (ignore && l.id == *ignore) return true;
          const double gap = track_gap(l, end);
          return gap >= rule.required() || gap >= current_gap(l) - 1e-9;
        });
        if (safe) return end;
      }
    }
  }
  return std::nullopt;
}

std::optional<double> parallax_range(double bearing0, const Vector2d& move, double bearing1) {
  // origin + t0·u0 = move + t1·u1
  const Vector2d u0 = unit(bearing0);
  const Vector2d u1 = unit(bearing1);
  const double det = -u0.x() * u1.y() + u0.y() * u1.x();
  if (std::abs(det) < 1e-6) return std::nullopt;
  const double t0 = (-move.x() * u1.y() + move.y() * u1.x()) / det;
  const double t1 = (u0.x() * move.y() - u0.y() * move.x()) / det;
  if (t0 <= 0 || t1 <= 0) return std::nullopt;
  return t1;
}

}  // namespace neopipe::nav::qualnav
