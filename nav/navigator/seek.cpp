// Seek (park-kender.md §3): the landmark a description selects in the current view, with the
// map-maker's own selection functions (nav/common/landmarks.hpp), so both choose alike.

#include <fmt/format.h>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

std::optional<Failure> seek(Pilot& pilot, const Eigen::Vector2d& reference, Description description,
                            Eigen::Vector2d& landmark) {
  const Sighting& seen = pilot.sighting();
  // The reference was located in this very sighting, so it is where it was last seen.
  const auto held = nearest(seen, reference, tracking_gate(0));
  if (!held) return Failure{Ending::lost, "lost sight of the reference landmark"};
  const auto chosen = select_landmark(description, View{seen.objects, *held});
  if (!chosen) {
    return Failure{Ending::lost, fmt::format("no {} landmark in view ({} objects besides the reference)",
                                             description_name(description), seen.objects.size() - 1)};
  }
  landmark = seen.objects[*chosen];
  return std::nullopt;
}

}  // namespace neopipe::nav::navigator::detail
