#pragma once
// What `neopipe nav` does alike for every system but Park & Kender's (qrm, qualnav, nx): the
// journey settings of the arm's options, one --from/--to journey planned with its ids checked and
// --as-trial's seed, and the landmarks the rig judged as JSON.

#include <memory>
#include <nlohmann/json.hpp>

#include "apps/nav_command.hpp"
#include "rig/journey.hpp"
#include "rig/navigation_system.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {

/// --sigma-move, --sigma-rot and --seed as a journey's settings.
rig::JourneySettings arm_journey_settings(const NavArgs& args);

/// One journey's plan and settings.
struct PlannedJourney {
  std::unique_ptr<rig::Plan> plan;  ///< null: the system cannot plan it (its words already printed)
  rig::JourneySettings settings;    ///< with --as-trial's seed
};

/// Plans --from/--to on `system`. Throws UsageError for ids outside the world, a start equal to the
/// goal or a negative --as-trial; an unreachable goal prints the system's words and returns no plan.
PlannedJourney plan_one_journey(const NavArgs& args, const sim::World& world, const rig::NavigationSystem& system);

/// [{"entry", "intended", "held", "offset", "correct"}, ...]: every claim the rig judged.
nlohmann::json held_landmarks_json(const rig::JourneyResult& result);

}  // namespace neopipe::apps
