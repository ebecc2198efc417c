#include "apps/nav_journey_support.hpp"

#include <fmt/format.h>

#include "apps/cli_support.hpp"
#include "rig/seeds.hpp"

namespace neopipe::apps {

rig::JourneySettings arm_journey_settings(const NavArgs& a) {
  rig::JourneySettings s;
  s.errors.sigma_move = a.sigma_move;
  s.errors.sigma_rot = a.sigma_rot;
  s.seed = a.seed;
  return s;
}

PlannedJourney plan_one_journey(const NavArgs& a, const sim::World& world, const rig::NavigationSystem& system) {
  const auto check_id = [&](const char* option, std::int64_t id) {
    if (id < 0 || id >= std::ssize(world.objects)) {
      throw UsageError{
          fmt::format("{} {}: the world's objects are 0 to {}", option, id, std::ssize(world.objects) - 1)};
    }
    return static_cast<std::uint32_t>(id);
  };
  const std::uint32_t from = check_id("--from", *a.from);
  const std::uint32_t to = check_id("--to", *a.to);
  if (from == to) throw UsageError{fmt::format("--from {} --to {}: the start is the goal", from, to)};
  PlannedJourney j;
  j.settings = arm_journey_settings(a);
  if (a.as_trial) {
    if (*a.as_trial < 0) throw UsageError{fmt::format("--as-trial {}: trials are numbered from 0", *a.as_trial)};
    j.settings.seed = rig::trial_seed(j.settings.seed, *a.as_trial);
  }
  try {
    j.plan = system.plan(from, to);
  } catch (const rig::UnreachableGoal& e) {
    print_error("nav", e.what());
  }
  return j;
}

nlohmann::json held_landmarks_json(const rig::JourneyResult& r) {
  nlohmann::json held = nlohmann::json::array();
  for (const rig::HeldLandmark& h : r.held) {
    held.push_back({{"entry", h.entry},
                    {"intended", h.intended},
                    {"held", h.actual},
                    {"offset", h.offset},
                    {"correct", h.correct}});
  }
  return held;
}

}  // namespace neopipe::apps
