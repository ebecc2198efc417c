// Adjust (park-kender.md §1): visual servoing of a landmark to a window corner. Each move is the
// displacement that would put the landmark exactly at the corner; the arm's real motion differs, so
// the navigator looks again and corrects until the landmark is within tolerance.

#include <fmt/format.h>

#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {

std::optional<Failure> adjust(Pilot& pilot, Eigen::Vector2d& landmark, Corner corner) {
  const Eigen::Vector2d target = pilot.window().corner_point(corner);
  for (int moves = 0;; ++moves) {
    const Eigen::Vector2d error = landmark - target;
    if (error.norm() <= pilot.config().adjust_tolerance) return std::nullopt;
    if (moves >= pilot.config().max_adjust_moves) {
      return Failure{Ending::lost, fmt::format("could not hold the landmark at {} in {} moves (still {:.2f} mm off)",
                                               corner_name(corner), moves, error.norm())};
    }
    // The landmark may start as a cap cut by the border (a trajectory's newcomer): track it among
    // everything seen.
    // A marble cut by the border is located less well (a deep cap by up to a millimetre or so).
    const double radius = pilot.config().camera.object_diameter / 2;
    const double side = pilot.window().side;
    const bool cut = landmark.minCoeff() < radius || landmark.maxCoeff() > side - radius;
    const std::vector<Eigen::Vector2d> seen = everything_seen(pilot.move_and_look(error));
    if (!pilot.moved()) {
      return Failure{Ending::lost,
                     fmt::format("the landmark cannot be held at {}: beyond the arm's reach", corner_name(corner))};
    }
    const auto i = nearest(seen, target, tracking_gate(error.norm()) + (cut ? radius : 0.0));
    if (!i) {
      return Failure{Ending::lost,
                     fmt::format("lost sight of the landmark while adjusting it to {}", corner_name(corner))};
    }
    landmark = seen[*i];
  }
}

}  // namespace neopipe::nav::navigator::detail
