#pragma once
// NX's exploration (qualnav.md §9): from wherever it starts, it climbs to a place and keeps an agenda
// of unexplored (place, edge) pairs. It travels by its map to the nearest pair, follows the edge
// and describes the place it ends at. That is a known place when its dead reckoning, anchored at
// every place it knows it stands at, puts one there (within Robot::position_radius) whose range
// agrees within 10 %; else a new place, stored with the odometry's position. Every
// travel and turn goes to TOUR as <view, action, view> (views: place, edge, and whether the robot
// leaves by that edge or has just arrived by it).

#include <cstddef>
#include <cstdint>
#include <string>

#include "nav/nx/learned_map.hpp"
#include "nav/nx/robot.hpp"
#include "nav/tour/cognitive_map.hpp"

namespace neopipe::nav::nx {

struct ExploreSettings {
  std::size_t max_places = 40;
  std::int64_t max_moves = 100000;
};

/// What the harness may watch (it records where a place really is; NX never hears back).
class ExploreObserver {
 public:
  virtual ~ExploreObserver() = default;
  /// A new place, where the robot now stands.
  virtual void place_found(std::size_t /*place*/) {}

 protected:
  ExploreObserver() = default;
  ExploreObserver(const ExploreObserver&) = default;
  ExploreObserver& operator=(const ExploreObserver&) = default;
};

struct ExploreReport {
  std::string ending;  ///< "agenda empty", "place budget", "move budget", "lost", "no place"
  std::size_t places = 0;
  std::size_t edges = 0;
  int open_edges = 0;
  int blocked_edges = 0;
  int matches = 0;            ///< arrivals at a known place (by dead reckoning and range)
  int arrivals_unlinked = 0;  ///< of those, where the known place had no free edge this way
  std::int64_t moves = 0;
  std::int64_t frames = 0;
  double travelled_mm = 0;
};

/// TOUR's view of NX's place `place` facing along its edge `slot`, leaving (false) or just arrived
/// by it (true).
tour::ViewId nx_view(std::size_t place, int slot, bool arrived);

/// Explores into `map` (empty at first). `tour` (optional) receives the <view, action, view> stream.
ExploreReport explore(Robot& robot, LearnedMap& map, const ExploreSettings& settings,
                      tour::CognitiveMap* tour = nullptr, ExploreObserver* observer = nullptr);

}  // namespace neopipe::nav::nx
