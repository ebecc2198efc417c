#pragma once
// NX travelling by its learned map (qualnav.md §9): from a place it is told it stands at, to a goal
// place, edge by edge (shortest by the edges' lengths), hill-climbing at every place and checking
// that it is the place the map expects (its range agrees within 10 %). At an unexpected place it re-localises among the
// places its description fits (best range agreement) and re-plans; with none it is lost. An edge that does not lead to
// a place is retraced (dead reckoning, then a climb) and avoided from then on. At the goal it measures the marble
// nearest a given compass bearing.

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

}  // namespace neopipe::nav::nx
