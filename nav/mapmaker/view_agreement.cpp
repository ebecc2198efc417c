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

}  // namespace neopipe::nav::mapmaker
