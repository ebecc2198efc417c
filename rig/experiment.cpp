#include "rig/experiment.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace neopipe::rig {

ExperimentSettings derive_settings(const ExperimentConfig& c, double survey_sigma) {
  if (!(c.window > 0) || !std::isfinite(c.window)) {
    throw std::invalid_argument(fmt::format("window {}: must be > 0 mm", c.window));
  }
  const auto check = [](const char* what, double v) {
    if (!(v >= 0) || !std::isfinite(v)) throw std::invalid_argument(fmt::format("{} {}: must be >= 0", what, v));
  };
  check("survey sigma", survey_sigma);
  check("arm translation error", c.arm.sigma_move);
  check("arm rotation error", c.arm.sigma_rot);
  if (!(c.min_reliability >= 0 && c.min_reliability <= 1)) {
    throw std::invalid_argument(fmt::format("least reliability {}: must be in [0, 1]", c.min_reliability));
  }

  ExperimentSettings s;
  s.min_reliability = c.min_reliability;
  s.map.window = nav::WindowModel::with_side(c.window);
  // The map-maker rates its steps with the errors the navigator really meets: the survey's position
  // error (as the survey states it, not as the truth would) and the navigator's own placement of its
  // window, which holds a landmark only to within its adjust tolerance (taken as two sd). Without
  // the second an exact survey makes every step look certain and the plan takes borderline ones
  // (docs/navigation-experiments.md, sensor accuracy).
  s.map.errors.sigma = std::hypot(survey_sigma, nav::navigator::NavigatorConfig{}.adjust_tolerance / 2);
  // Where the survey and the world may disagree about which side of a border an object lies: 3 sd
  // of two objects' relative survey error, plus the navigator's own error on marbles the image border
  // cuts, plus where it holds its window (a landmark is held anywhere within the adjust tolerance of
  // its corner). The map-maker keeps its verification and recovery rules clear of that band; the
  // navigator uses the same band to explain a QOC or a view that differs from the map's.
  const double border_band =
      3 * std::sqrt(2.0) * survey_sigma + kNavigatorBorderError + nav::navigator::NavigatorConfig{}.adjust_tolerance;
  s.map.border_tolerance = border_band;
  s.map.extended_descriptions = c.extended_descriptions;
  s.map.slide_goals = c.slide_goals;
  s.navigator.slide_goals = c.slide_goals;
  s.map.errors.translation_per_mm = c.arm.sigma_move;
  s.map.errors.rotation_per_mm = c.arm.sigma_rot * std::numbers::pi / 180;
  // The map-maker rates its steps with what this navigator recovers from (nothing without recovery).
  if (c.recovery) s.map.errors.recovery = nav::mapmaker::RecoveryCredit::fitted();
  s.navigator.window = s.map.window;
  s.navigator.view_margin = border_band;
  // A slide that led nowhere is tried again beside its track, as far as the survey's errors move it.
  s.navigator.slide_offset = kSlideOffsetPerSigma * survey_sigma;
  s.navigator.recovery = c.recovery;
  s.navigator.track_heading = c.track_heading;
  // What the navigator expects its arm to turn by error is what the arm is configured to do.
  s.navigator.turn_sigma_per_mm = s.map.errors.rotation_per_mm;
  s.journey.errors = c.arm;
  s.journey.realism = c.realism;
  s.journey.seed = c.seed;
  return s;
}

std::unique_ptr<ParkKenderSystem> make_park_kender(const Survey& survey, const ExperimentSettings& settings,
                                                   nav::mapmaker::CostCriterion criterion,
                                                   nav::navigator::Observer* observer) {
  auto system =
      std::make_unique<ParkKenderSystem>(survey.workspace, settings.map, criterion, settings.navigator, observer);
  system->refuse_below(settings.min_reliability);
  return system;
}

}  // namespace neopipe::rig
