#include "nav/nx/journey.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace neopipe::nav::nx {

const char* journey_ending_name(JourneyEnding e) {
  switch (e) {
    case JourneyEnding::arrived:
      return "arrived";
    case JourneyEnding::not_at_start:
      return "not_at_start";
    case JourneyEnding::no_route:
      return "no_route";
    case JourneyEnding::lost:
      return "lost";
    case JourneyEnding::blocked:
      return "blocked";
    case JourneyEnding::leg_limit:
      return "leg_limit";
  }
  return "lost";
}

NxJourney travel_to_place(Robot& robot, const LearnedMap& map, std::size_t start, std::size_t goal) {
  const NxConfig& c = robot.config();
  NxJourney j;
  const auto end = [&](JourneyEnding e, std::string reason) {
    j.ending = e;
    j.reason = std::move(reason);
    return j;
  };
  if (climb_to_place(robot).ending != ClimbEnding::place) return end(JourneyEnding::not_at_start, "no place here");
  const std::optional<PlaceView> here = describe_place(robot);
  if (!here || !map.range_fits(start, *here, c.match_tolerance)) {
    return end(JourneyEnding::not_at_start, "this place does not look like the start");
  }
  std::size_t at = start;
  j.places.push_back(at);
  std::set<std::pair<std::size_t, int>> failed;  // legs that did not arrive, avoided from then on
  const int max_legs = 3 * static_cast<int>(map.size()) + 10;
  while (at != goal) {
    if (j.legs >= max_legs) return end(JourneyEnding::leg_limit, "too many legs");
    const std::vector<Leg> route = map.route(at, goal, failed);
    if (route.empty()) {
      return end(j.detours > 0 ? JourneyEnding::lost : JourneyEnding::no_route,
                 j.detours > 0 ? "no route left around the edges that failed" : "the map has no route from here");
    }
    const Leg& leg = route.front();
    const Slot& s = map.place(leg.place).slots.at(static_cast<std::size_t>(leg.slot));
    robot.read_heading();
    const EdgeRun run = follow_edge(robot, s.heading_deg);
    ++j.legs;
    if (run.ending != EdgeEnding::arrived) {
      // Recovery: back to the place by dead reckoning and a climb, and plan around this edge.
      if (retrace(robot, run).ending != ClimbEnding::place) {
        return end(run.ending == EdgeEnding::blocked ? JourneyEnding::blocked : JourneyEnding::lost,
                   "the edge did not lead to a place, and no way back");
      }
      failed.insert({leg.place, leg.slot});
      ++j.detours;
      continue;
    }
    const std::optional<PlaceView> view = describe_place(robot);
    if (!view) return end(JourneyEnding::lost, "no place at the end of the edge");
    // The expected place: its headings may be blurred by noise, so twice the matching tolerance.
    if (map.could_be(s.to_place, *view, c.match_tolerance, 2 * c.heading_tolerance_deg, 2)) {
      at = s.to_place;
    } else {
      const std::vector<std::size_t> fits = map.candidates(*view, c.match_tolerance, c.heading_tolerance_deg);
      if (fits.empty()) return end(JourneyEnding::lost, "an unknown place");
      at = fits.front();
      ++j.relocalisations;
    }
    j.places.push_back(at);
  }
  j.ending = JourneyEnding::arrived;
  return j;
}

std::optional<Eigen::Vector2d> locate_marble(Robot& robot, double bearing_deg, int reads) {
  robot.read_heading();
  const std::vector<Neighbour> n = robot.neighbours(3, reads);
  std::optional<Eigen::Vector2d> best;
  double best_off = 45;
  for (const Neighbour& m : n) {
    const double off = std::abs(wrap180(robot.compass_heading(-m.away) - bearing_deg));
    if (off <= best_off) {
      best = -m.away * m.range;
      best_off = off;
    }
  }
  return best;
}

}  // namespace neopipe::nav::nx
