// Trajectories (park-kender.md §4): the window slides along the line reference -> landmark (Trajp)
// or back (Trajn) in short steps. Everything in view at the start is tracked by its predicted
// place; the first object seen that is none of them has entered through the leading edges, and is
// the trajectory's goal, as the map-maker's sweep (mapmaker/trajectories.cpp) predicts.

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {
namespace {

// How far back along the slide the object now at `q` entered the window: it was at q + s u, inside
// while 0 < q_k + s u_k < a on both axes. The larger, the earlier it entered.
double entered_ago(const Eigen::Vector2d& q, const Eigen::Vector2d& u, double side) {
  double back = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    if (u[k] > 0) back = std::min(back, (side - q[k]) / u[k]);
    if (u[k] < 0) back = std::min(back, q[k] / -u[k]);
  }
  return back;
}

}  // namespace

std::optional<Failure> slide(Pilot& pilot, const Eigen::Vector2d& reference, const Eigen::Vector2d& via,
                             Direction direction, Eigen::Vector2d& found) {
  const NavigatorConfig& config = pilot.config();
  const double side = config.window.side;
  const Eigen::Vector2d line = via - reference;
  if (line.norm() == 0) return Failure{Ending::lost, "the trajectory's two landmarks coincide"};
  const Eigen::Vector2d heading =
      direction == Direction::positive ? line.normalized() : Eigen::Vector2d(-line.normalized());

  // Known objects, by where they are expected now. Kept after they leave the window (until well
  // past its edge), so one flickering at the trailing edge is not taken for a newcomer.
  std::vector<Eigen::Vector2d> known = pilot.sighting().objects;
  Eigen::Vector2d origin_reference = reference;  // the reference's predicted place: ties are broken from it
  std::vector<char> matched;
  std::vector<std::size_t> newcomers;
  for (double slid = 0; slid < config.max_slide;) {
    const double step = std::min(config.slide_step, config.max_slide - slid);
    const Eigen::Vector2d d = step * heading;
    for (Eigen::Vector2d& p : known) p -= d;
    origin_reference -= d;
    const Sighting& seen = pilot.move_and_look(d);
    slid += step;

    const double gate = tracking_gate(step);
    matched.assign(known.size(), 0);
    newcomers.clear();
    for (std::size_t i = 0; i < seen.objects.size(); ++i) {
      std::optional<std::size_t> best;
      double best_d2 = gate * gate;
      for (std::size_t k = 0; k < known.size(); ++k) {
        const double d2 = (seen.objects[i] - known[k]).squaredNorm();
        if (!matched[k] && d2 <= best_d2) {
          best = k;
          best_d2 = d2;
        }
      }
      if (best) {
        matched[*best] = 1;
        known[*best] = seen.objects[i];
      } else {
        newcomers.push_back(i);
      }
    }
    if (!newcomers.empty()) {
      // Several may have come in during one step: the goal is the one that entered first.
      std::size_t goal = newcomers.front();
      for (const std::size_t i : newcomers) {
        const double ago = entered_ago(seen.objects[i], heading, side);
        const double best = entered_ago(seen.objects[goal], heading, side);
        if (ago > best || (ago == best && preferred(origin_reference, seen.objects[i], seen.objects[goal]))) goal = i;
      }
      found = seen.objects[goal];
      return std::nullopt;
    }
    std::erase_if(known,
                  [&](const Eigen::Vector2d& p) { return (p.array() < -side).any() || (p.array() > 2 * side).any(); });
  }
  return Failure{Ending::lost, fmt::format("slid {:.0f} mm along the trajectory ({}) without meeting an object",
                                           config.max_slide, trajectory_name(direction))};
}

}  // namespace neopipe::nav::navigator::detail
