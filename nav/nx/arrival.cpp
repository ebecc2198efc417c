#include "nav/nx/arrival.hpp"

#include <algorithm>
#include <vector>

#include "nav/nx/controls.hpp"

namespace neopipe::nav::nx {
namespace {

// Places whose stored positions lie this close are one junction (see below).
constexpr double kJunctionMm = 2;

}  // namespace

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
  const bool expected_near =
      expected && expected != exclude && std::find(near.begin(), near.end(), *expected) != near.end();
  Arrival a;
  for (const std::size_t q : near) {
    if (q == exclude || !looks_like(q)) continue;
    if (q == expected) return {q, true};
    if (!a.place) a.place = q;
  }
  if (a.place) {
    // Four nearly co-circular marbles make two vertices (places) within a mm or two, one junction
    // of four edges: NX's plan may go on from the expected one.
    if (expected_near && (map.place(*expected).position - map.place(*a.place).position).norm() <= kJunctionMm) {
      return {expected, true};
    }
    return a;
  }
  if (expected_near) return {expected, true};  // where it should be, its headings blurred
  // The expected place by its description alone: where two chains of dead reckoning met (a loop
  // closed), the stored positions of neighbours may disagree by more than the reach, though not by
  // much more.
  if (expected && *expected != exclude && looks_like(*expected) &&
      (map.place(*expected).position - robot.odometry()).norm() <= 3 * radius) {
    return {expected, true};
  }
  for (const std::size_t q : near) {
    if (q != exclude) return {q, false};
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
