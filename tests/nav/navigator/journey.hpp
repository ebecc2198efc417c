#pragma once
// One journey of the navigator on the simulator along a route planned by the map-maker, with the
// ground truth the tests judge it by.

#include <chrono>

#include "nav/mapmaker/map_maker.hpp"
#include "sim_rig.hpp"

namespace neopipe::nav::navigator::test_rig {

struct Journey {
  JourneyReport report;
  std::vector<std::pair<std::size_t, Eigen::Vector2d>> held;  ///< per entry reached: world position held
  std::size_t final_object = 0;  ///< the object nearest where the navigator ended holding its landmark
  double final_offset = 0;       ///< mm from that object
  double seconds = 0;
};

inline mapmaker::Workspace workspace_of(const sim::World& world) {
  return {world.size, world.objects};
}

inline Journey travel(Rig& rig, const CustomMap& map, std::size_t start, Corner start_corner) {
  rig.hold(start, start_corner);
  TruthObserver observer(rig);
  Journey j;
  const auto t0 = std::chrono::steady_clock::now();
  j.report = follow(map, rig.eye(), rig.arm(), rig.config(), &observer);
  j.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  j.held = observer.held;
  if (!j.held.empty()) std::tie(j.final_object, j.final_offset) = rig.nearest_object(j.held.back().second);
  return j;
}

inline Journey travel(Rig& rig, const mapmaker::Route& route) {
  return travel(rig, route.custom_map, route.start, route.start_corner);
}

}  // namespace neopipe::nav::navigator::test_rig
