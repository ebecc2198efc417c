#include "nav/nx/journey.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "nav/nx/arrival.hpp"

namespace neopipe::nav::nx {
namespace {

// Times a journey falls back on the edges it gave up on when no route is left without them.
constexpr int kLastResorts = 16;

}  // namespace

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
  robot.set_odometry(map.place(start).position);
  j.places.push_back(at);
  std::map<std::pair<std::size_t, int>, int> failures;  // per leg
  std::set<std::pair<std::size_t, int>> failed;         // legs avoided from then on
  const auto count_failure = [&](const Leg& leg) {
    ++j.detours;
    if (++failures[{leg.place, leg.slot}] >= c.failures_to_avoid) failed.insert({leg.place, leg.slot});
  };
  const int max_legs = 3 * static_cast<int>(map.size()) + 10;
  int last_resorts = 0;
  while (at != goal) {
    if (j.legs >= max_legs) return end(JourneyEnding::leg_limit, "too many legs");
    std::vector<Leg> route = map.route(at, goal, failed);
    // No way round the edges given up on: the map's edges are few (often a chain), and an edge that
    // failed twice may still arrive (its far place is one where a climb sometimes stops short), so
    // as a last resort it is tried again, a few times per journey.
    if (route.empty() && !failed.empty() && last_resorts++ < kLastResorts) route = map.route(at, goal);
    if (route.empty()) {
      return end(j.detours > 0 ? JourneyEnding::lost : JourneyEnding::no_route,
                 j.detours > 0 ? "no route left around the edges that failed" : "the map has no route from here");
    }
    const Leg& leg = route.front();
    const Slot& s = map.place(leg.place).slots.at(static_cast<std::size_t>(leg.slot));
    robot.read_heading();
    const EdgeRun run = follow_edge(robot, s.heading_deg);
    ++j.legs;
    std::optional<PlaceView> view;
    if (run.ending == EdgeEnding::arrived) view = describe_place(robot);
    Arrival a = view ? identify_arrival(robot, map, *view, s.to_place) : Arrival{};
    if (!a.place) a = climb_again_at(robot, map, s.to_place, 2);
    if (!a.place) {
      // Recovery: back to the place by dead reckoning and a climb, and plan again (around this edge
      // once it has failed often enough).
      if (retrace(robot, run).ending != ClimbEnding::place) {
        return end(run.ending == EdgeEnding::blocked ? JourneyEnding::blocked : JourneyEnding::lost,
                   "the edge did not lead to a known place, and no way back");
      }
      count_failure(leg);
      robot.set_odometry(map.place(at).position);
      continue;
    }
    if (!a.expected) {
      count_failure(leg);
      ++j.relocalisations;
    }
    at = *a.place;
    robot.set_odometry(map.place(at).position);
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

std::optional<Eigen::Vector2d> approach_marble(Robot& robot, double bearing_deg, double distance_mm, int reads) {
  const std::optional<Eigen::Vector2d> far = locate_marble(robot, bearing_deg, reads);
  if (!far) return far;
  const double range = far->norm();
  const double keep = std::max(distance_mm, robot.config().clearance_mm + 1);
  // Straight toward the marble: from a place its two neighbours lie no nearer that line than it
  // does, so it stays the nearest marble all the way.
  if (range > keep && !robot.move(*far * ((range - keep) / range))) return far;
  const double seen = robot.compass_heading(*far);
  return locate_marble(robot, seen, reads);
}

}  // namespace neopipe::nav::nx
