// Seek (park-kender.md §3): the landmark a description selects in the view of the held landmark,
// with the map-maker's own selection functions (nav/common/landmarks.hpp), so both choose alike.

#include <fmt/format.h>

#include <algorithm>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

namespace {

// The map says Obvious: the map-maker saw exactly one object besides the reference. When the view
// as seen has none or several, objects within the view margin of a border may be on the other side
// for the map-maker: the one object consistent with that, if there is one.
std::optional<Eigen::Vector2d> obvious_within_margin(const HeldView& view, double margin) {
  std::vector<std::size_t> clear;
  for (std::size_t i = 0; i < view.points.size(); ++i) {
    if (i != view.reference && view.depth[i] > margin) clear.push_back(i);
  }
  if (clear.size() == 1) return view.points[clear.front()];
  if (!clear.empty()) return std::nullopt;
  // Nothing clearly in view: the marginal object most likely to have been inside.
  std::optional<Eigen::Vector2d> best;
  double best_depth = -margin;
  for (std::size_t i = 0; i < view.points.size(); ++i) {
    if (i != view.reference && view.depth[i] > best_depth) {
      best = view.points[i];
      best_depth = view.depth[i];
    }
  }
  for (std::size_t i = 0; i < view.just_outside.size(); ++i) {
    if (view.outside_depth[i] > best_depth) {
      best = view.just_outside[i];
      best_depth = view.outside_depth[i];
    }
  }
  return best;
}

}  // namespace

std::optional<Failure> seek(Pilot& pilot, const Hold& hold, Description description, Eigen::Vector2d& landmark) {
  const double margin = pilot.config().view_margin;
  const HeldView view = held_view(pilot.sighting(), hold, pilot.window(), pilot.heading(), margin);
  const auto chosen = select_landmark(description, View{view.points, view.reference});
  if (!chosen && description == Description::Obvious) {
    if (const auto obvious = obvious_within_margin(view, margin)) {
      landmark = *obvious;
      return std::nullopt;
    }
  }
  if (!chosen && view.points.size() == 1 && !view.just_outside.empty()) {
    // Nothing in view, but the map-maker saw something: the object just outside most likely to be it.
    const auto deepest = std::max_element(view.outside_depth.begin(), view.outside_depth.end());
    landmark = view.just_outside[static_cast<std::size_t>(deepest - view.outside_depth.begin())];
    return std::nullopt;
  }
  if (!chosen) {
    return Failure{Ending::lost, fmt::format("no {} landmark in view ({} objects besides the reference)",
                                             description_name(description), view.points.size() - 1)};
  }
  landmark = view.points[*chosen];
  return std::nullopt;
}

}  // namespace neopipe::nav::navigator::detail
