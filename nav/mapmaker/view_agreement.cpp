#include "nav/mapmaker/view_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "nav/mapmaker/normal.hpp"

namespace neopipe::nav::mapmaker {
namespace {

// Beyond this many standard deviations from an edge a flip changes R by less than 3e-7.
constexpr double kReach = 5.0;

}  // namespace

double view_agreement(const WorldViews& views, const Placement& from, Description description, double sigma) {
  if (!(sigma > 0)) return 1.0;
  const double sd = std::numbers::sqrt2 * sigma;
  const double a = views.window().side;
  const Eigen::Vector2d origin = views.origin(from);
  const double reach = kReach * sd;
  const Eigen::Vector2d widen(reach, reach);
  const std::span<const std::uint32_t> visible = views.visible(from);
  const std::optional<std::uint32_t> predicted = views.landmark(from, description);

  // The view as ids, so a flipped one can be judged with the descriptors the navigator runs.
  std::vector<std::uint32_t> ids(visible.begin(), visible.end());
  const auto selects = [&](const std::vector<std::uint32_t>& in_view) -> std::optional<std::uint32_t> {
    std::vector<Eigen::Vector2d> points;
    std::size_t reference = 0;
    for (std::size_t i = 0; i < in_view.size(); ++i) {
      if (in_view[i] == from.object) reference = i;
      points.push_back(views.position(in_view[i]));
    }
    const auto chosen = select_landmark(description, View{points, reference});
    return chosen ? std::optional<std::uint32_t>(in_view[*chosen]) : std::nullopt;
  };

  double agreement = 1.0;
  views.grid().for_each_near(origin - widen, origin + Eigen::Vector2d(a, a) + widen, [&](std::uint32_t id) {
    if (id == from.object) return;
    const Eigen::Vector2d q = views.position(id) - origin;
    // Signed distance to the window's boundary: > 0 inside (to the nearest edge), < 0 outside (to
    // the edge the object would have to cross last).
    const double inside = std::min({q.x(), a - q.x(), q.y(), a - q.y()});
    if (std::abs(inside) >= reach) return;
    const bool in_view = std::binary_search(visible.begin(), visible.end(), id);
    if (in_view != (inside > 0)) return;  // on the edge exactly: `sees` already decided
    std::vector<std::uint32_t> flipped = ids;
    if (in_view) {
      flipped.erase(std::find(flipped.begin(), flipped.end(), id));
    } else {
      flipped.insert(std::upper_bound(flipped.begin(), flipped.end(), id), id);
    }
    if (selects(flipped) != predicted) agreement *= normal_cdf(std::abs(inside) / sd);
  });
  return agreement;
}

// w400's 391 -> 120 is why: two marbles enter by the window's bottom edge 0.03 mm of depth apart;
// rated certain by the slide's geometry, it lost half the journeys through it.
double entry_order_agreement(const WorldViews& views, const Trajectory& trajectory, double sigma) {
  if (!(sigma > 0)) return 1.0;
  const double a = views.window().side;
  const Eigen::Vector2d heading = trajectory.heading(views);
  const Eigen::Vector2d start = views.origin(trajectory.from);
  // The edge an object enters by: the one it lies on when it enters (x: a vertical edge).
  const auto by_vertical_edge = [&](const Eigen::Vector2d& p, double slide) {
    const Eigen::Vector2d at = p - (start + slide * heading);
    return std::min(std::abs(at.x()), std::abs(at.x() - a)) < std::min(std::abs(at.y()), std::abs(at.y() - a));
  };
  const Eigen::Vector2d goal = views.position(trajectory.to);
  const bool vertical = by_vertical_edge(goal, trajectory.slide);
  const double rate = std::abs(vertical ? heading.x() : heading.y());  // depth gained per mm of slide
  if (!(rate > 0)) return 1.0;
  const double sd = std::numbers::sqrt2 * sigma;
  const double lag_reach = std::min(kReach * sd / rate, a);
  // Objects that enter within that lag lie in the window's footprint over those slides.
  const Eigen::Vector2d from = start + trajectory.slide * heading;
  const Eigen::Vector2d to = from + lag_reach * heading;
  const Eigen::Vector2d lo = from.cwiseMin(to);
  const Eigen::Vector2d hi = from.cwiseMax(to) + Eigen::Vector2d(a, a);
  double agrees = 1.0;
  views.grid().for_each_near(lo, hi, [&](std::uint32_t id) {
    if (id == trajectory.to || id == trajectory.from.object || id == trajectory.via) return;
    const Eigen::Vector2d& p = views.position(id);
    const auto t = entry_distance(views.window(), start, heading, p);
    if (!t || *t <= trajectory.slide || *t > trajectory.slide + lag_reach) return;
    if (by_vertical_edge(p, *t) != vertical) return;  // another edge: trajectory_reliability's bounds
    agrees *= normal_cdf((*t - trajectory.slide) * rate / sd);
  });
  return agrees;
}

}  // namespace neopipe::nav::mapmaker
