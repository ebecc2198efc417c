#pragma once
// One journey: the rig builds the station (arm and onboard camera over the world), places the arm
// where the plan starts, lets the system travel, and judges every landmark the system claimed to
// hold against the ground truth (rig/outcome.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rig/navigation_system.hpp"
#include "rig/outcome.hpp"
#include "rig/station.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// Whether the landmark a system claimed at one entry was the one its plan meant.
struct HeldLandmark {
  std::size_t entry = 0;
  std::uint32_t intended = 0;  ///< the plan's object for this entry
  std::uint32_t actual = 0;    ///< the world object nearest to where the system held it
  double offset = 0;           ///< mm between that object and the held position
  bool correct = false;
  Eigen::Vector2d tool{0, 0};  ///< where the tool really was, mm
};

struct JourneyResult {
  Travel travel;  ///< the system's own account
  Outcome outcome = Outcome::fail_lost;
  std::vector<HeldLandmark> held;  ///< every claim, in order
  ArmLog arm;                      ///< what the arm really did
  std::int64_t frames = 0;
};

/// The journey's simulated equipment, apart from what the system's camera request fixes.
struct JourneySettings {
  ArmErrors errors;
  sim::Realism realism = sim::Realism::rig;  ///< of the onboard camera
  std::uint64_t seed = 1;                    ///< arm errors and camera noise of this journey
};

/// Judges a journey from its claims: the last claim of each entry counts (a recovery may hold an
/// entry again); entry 0 is the start, placed by the rig, so only the later entries must be claimed.
JourneyTruth judge(const std::vector<HeldLandmark>& held, const Plan& plan, const Travel& travel);

/// Runs `plan` (made by `system` on a survey of `world`) as one journey. Never throws for a
/// navigation failure.
JourneyResult run_journey(const NavigationSystem& system, const Plan& plan, const sim::World& world,
                          const JourneySettings& settings);

}  // namespace neopipe::rig
