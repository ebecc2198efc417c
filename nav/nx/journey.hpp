#pragma once
// NX travelling by its learned map (qualnav.md §9): from a place it is told it stands at, to a goal
// place, edge by edge (shortest by the edges' lengths), hill-climbing at every place and checking
// that it is the place the map expects (by its dead reckoning, anchored at every place, and its range:
// identify_arrival). At another known place it re-localises there and re-plans. An edge that does not lead to a
// known place is retraced (dead reckoning, then a climb) and avoided once it has failed
// NxConfig::failures_to_avoid times. At the goal it measures the marble nearest a given compass bearing.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "nav/nx/learned_map.hpp"
#include "nav/nx/robot.hpp"

namespace neopipe::nav::nx {

enum class JourneyEnding { arrived, not_at_start, no_route, lost, blocked, leg_limit };
inline constexpr std::size_t kJourneyEndings = 6;
const char* journey_ending_name(JourneyEnding e);

struct NxJourney {
  JourneyEnding ending = JourneyEnding::lost;
  std::string reason;
  std::vector<std::size_t> places;  ///< visited, the start first
  int legs = 0;
  int relocalisations = 0;
  int detours = 0;  ///< edges that did not arrive: NX went back and planned around them
};

/// Travels from place `start` (where the robot has been put, near it) to place `goal`.
NxJourney travel_to_place(Robot& robot, const LearnedMap& map, std::size_t start, std::size_t goal);

/// The marble seen nearest compass bearing `bearing_deg` among the three nearest, as the nearest
/// point of its surface in the tool frame (mm); nullopt when none is within 45°. `reads` frames per
/// look (more than the journey's, for precision).
std::optional<Eigen::Vector2d> locate_marble(Robot& robot, double bearing_deg, int reads);

/// Moves straight toward the marble that locate_marble finds until its surface is `distance_mm`
/// away (never nearer than the clearance), then locates it again: the nearer the marble, the less a
/// range's relative error and a gradient's direction error put the surface point off, in mm.
std::optional<Eigen::Vector2d> approach_marble(Robot& robot, double bearing_deg, double distance_mm, int reads);

}  // namespace neopipe::nav::nx
