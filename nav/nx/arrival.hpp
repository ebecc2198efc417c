#pragma once
// Where NX has arrived after following an edge (qualnav.md §9, Decision): the known place that its
// dead reckoning puts within reach (Robot::position_radius) and whose range agrees, nearest first.
// A place's description alone (range and edge headings) fits many places of a world of equal marbles,
// and under range error the right one may not fit at all; the odometry, anchored at every known
// place, tells them apart.

#include <cstddef>
#include <optional>

#include "nav/nx/learned_map.hpp"
#include "nav/nx/robot.hpp"

namespace neopipe::nav::nx {

struct Arrival {
  std::optional<std::size_t> place;  ///< nullopt: no known place here
  bool expected = false;             ///< the place the map expected
};

/// The known place the robot stands at, described as `view`, after travelling toward `expected`
/// (nullopt: nothing expected, as at the end of an unexplored edge; `exclude`: a place it cannot be).
Arrival identify_arrival(const Robot& robot, const LearnedMap& map, const PlaceView& view,
                         std::optional<std::size_t> expected, std::optional<std::size_t> exclude = std::nullopt);

/// After an edge toward `expected` that ended where the odometry puts `expected` (within the reach)
/// but not at a place NX knows (a climb there that stopped short or slid to a neighbour): climbs
/// again, up to `tries` times, and identifies the arrival. nullopt place when the odometry is elsewhere
/// or no climb settles.
Arrival climb_again_at(Robot& robot, const LearnedMap& map, std::size_t expected, int tries);

}  // namespace neopipe::nav::nx
