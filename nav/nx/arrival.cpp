#include "nav/nx/arrival.hpp"

#include <vector>

#include "nav/nx/controls.hpp"

namespace neopipe::nav::nx {

Arrival identify_arrival(const Robot& robot, const LearnedMap& map, const PlaceView& view,
                         std::optional<std::size_t> expected, std::optional<std::size_t> exclude) {
  const NxConfig& c = robot.config();
  const double radius = robot.position_radius();
  const std::vector<std::size_t> near = map.near(robot.odometry(), radius, view, c.match_tolerance);
  // Vertices a few mm apart (nearly co-circular marbles) both lie within reach: of those, the ones
  // whose edge headings agree come first (two of three, within twice the tolerance: noise blurs one).
  const auto looks_like = [&](std::size_t q) {
    return map.could_be(q, view, c.match_tolerance, 2 * c.heading_tolerance_deg, 2);
  };
  Arrival a;
  for (const std::size_t q : near) {
    if (q == exclude || !looks_like(q)) continue;
    if (q == expected) return {q, true};
    if (!a.place) a.place = q;
  }
  if (a.place) return a;
  // The expected place by its description alone: where two chains of dead reckoning met (a loop
  // closed), the stored positions of neighbours may disagree by more than the reach.
  if (expected && *expected != exclude && looks_like(*expected)) return {expected, true};
  for (const std::size_t q : near) {
    if (q != exclude) return {q, q == expected};
  }
  return a;
}

Arrival climb_again_at(Robot& robot, const LearnedMap& map, std::size_t expected, int tries) {
  for (int i = 0; i < tries; ++i) {
    if ((map.place(expected).position - robot.odometry()).norm() > robot.position_radius()) return {};
    if (climb_to_place(robot).ending != ClimbEnding::place) continue;
    const std::optional<PlaceView> view = describe_place(robot);
    if (!view) continue;
    const Arrival a = identify_arrival(robot, map, *view, expected);
    if (a.place) return a;
  }
  return {};
}

}  // namespace neopipe::nav::nx
