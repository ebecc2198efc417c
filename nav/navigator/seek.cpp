// Seek (park-kender.md §3): the landmark a description selects in the view of the held landmark,
// with the map-maker's own selection functions (nav/common/landmarks.hpp), so both choose alike.

#include <fmt/format.h>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

std::optional<Failure> seek(Pilot& pilot, const Hold& hold, Description description, Eigen::Vector2d& landmark) {
  const HeldView view = held_view(pilot.sighting(), hold, pilot.window(), pilot.heading());
  const auto chosen = select_landmark(description, View{view.points, view.reference});
  if (!chosen) {
    return Failure{Ending::lost, fmt::format("no {} landmark in view ({} objects besides the reference)",
                                             description_name(description), view.points.size() - 1)};
  }
  landmark = view.points[*chosen];
  return std::nullopt;
}

}  // namespace neopipe::nav::navigator::detail
