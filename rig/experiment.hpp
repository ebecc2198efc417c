#pragma once
// An experiment's settings, derived in one place: from what the command line states (the view
// window, the arm's errors, recovery on or off) and the survey's told
// position error, the map-maker's error model and border band and the navigator's view margin.
// `neopipe nav`, the benchmarks and the tests all take them from here, so the code behind the
// published numbers is the code the tests exercise.

#include <memory>

#include "nav/mapmaker/map_maker.hpp"
#include "nav/navigator/navigator.hpp"
#include "rig/journey.hpp"
#include "rig/park_kender.hpp"
#include "rig/station.hpp"
#include "rig/survey.hpp"

namespace neopipe::rig {

struct ExperimentConfig {
  double window = 50;  ///< view window side a, mm
  ArmErrors arm;
  bool recovery = true;                      ///< the navigator applies the map's recovery rules
  bool track_heading = true;                 ///< navigator "tracking" (true) or "paper" (false)
  bool extended_descriptions = true;         ///< the map's descriptions: "extended" (with Far, Near) or "paper"
  bool slide_goals = true;                   ///< the map says where each slide's goal enters (SlideGoal)
  double min_reliability = 0;                ///< routes forecast below this are refused
  sim::Realism realism = sim::Realism::rig;  ///< of the onboard camera (the survey has its own)
  std::uint64_t seed = 1;                    ///< arm errors and camera noise (journey i: trial_seed(seed, i))
};

/// mm: how far the navigator may misjudge a marble cut by its image border (its centre from the cap)
/// and the turn it has not measured, at the far side of its window.
inline constexpr double kNavigatorBorderError = 0.25;

/// How far beside its track a slide that led nowhere is tried again, per mm of survey sd: about 2.8
/// sd of two objects' relative error. Measured at 2.5, 4 and 6 mm for sigma 1 and 1.5 (issue 17):
/// 2.5 mm recovers less, 4 to 6 mm about alike.
inline constexpr double kSlideOffsetPerSigma = 4.0;

struct ExperimentSettings {
  double min_reliability = 0;
  nav::mapmaker::MapMakerOptions map;
  nav::navigator::NavigatorConfig navigator;
  JourneySettings journey;
};

/// Throws std::invalid_argument for a window that is not positive or arm errors that are negative
/// or not finite, naming the setting.
ExperimentSettings derive_settings(const ExperimentConfig& config, double survey_sigma);

/// Park & Kender's system planning on `survey` with the derived settings.
std::unique_ptr<ParkKenderSystem> make_park_kender(const Survey& survey, const ExperimentSettings& settings,
                                                   nav::mapmaker::CostCriterion criterion,
                                                   nav::navigator::Observer* observer = nullptr);

}  // namespace neopipe::rig
