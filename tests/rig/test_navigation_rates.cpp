// Statistical guards on the navigation system's published rates (docs/navigation-experiments.md),
// with the power to see a fall that matters. Each runs the same journeys as `neopipe nav --trials N
// --sigma-map S --seed 1` on the default sparse world (and one dense world), and asks that the 95% lower bound of the
// share reaching the goal stay above the published level less 2 points. The journeys are enough
// that the bound lies 0.5-0.6 (99.7-99.9%, 1,000 journeys) and 1.0 point (95%, 2,000) under the rate: a
// harmless change keeps it with room for its noise, and a 2-point fall fails (the bound then lies
// about 3 points under the level). The forecast is checked on the same journeys: its mean within 2
// points of the rate. Its bins of planned R are printed, not asserted: one survey's errors are shared
// by every journey here, so the bins are judged over many surveys (scripts/nav_experiments.py
// surveys, docs/navigation-experiments.md).
// Deterministic: the same seeds give the same journeys, so these tests never flake.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>

#include "rig/experiment.hpp"
#include "rig/outcome.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
namespace sim = neopipe::sim;
namespace mm = neopipe::nav::mapmaker;

rig::TrialsSummary trials_at(double survey_sigma, std::int64_t journeys, int objects = 100) {
  sim::WorldRequest q;
  q.objects = objects;
  q.seed = 1;
  const sim::World world = sim::generate_world(q);
  const rig::Survey survey = rig::gaussian_survey(world, survey_sigma, 1);
  rig::ExperimentConfig c;
  c.seed = 1;
  const rig::ExperimentSettings settings = rig::derive_settings(c, survey.sigma);
  const auto system = rig::make_park_kender(survey, settings, mm::CostCriterion::reliability);
  const auto plans = rig::draw_plans(*system, world.objects.size(), journeys, c.seed);
  return rig::run_trials(*system, plans, world, settings.journey, 0);
}

void expect_level_and_calibrated_forecast(const rig::TrialsSummary& t, double level) {
  ASSERT_EQ(t.refused, 0);
  const double rate = static_cast<double>(t.reached()) / static_cast<double>(t.run());
  const rig::Interval ci = rig::wilson_interval(t.reached(), t.run());
  std::cout << "reached " << t.reached() << " of " << t.run() << " [" << ci.low << ", " << ci.high << "], forecast "
            << t.mean_planned_reliability() << "\n";
  EXPECT_GE(ci.low, level - 0.02) << "the rate fell: " << rate << " against the published " << level;
  EXPECT_LE(std::abs(t.mean_planned_reliability() - rate), 0.02) << "the forecast is off";
  constexpr std::array kEdges{0.0, 0.8, 0.9, 0.97, 1.0000001};
  for (std::size_t b = 0; b + 1 < kEdges.size(); ++b) {
    std::int64_t n = 0, reached = 0;
    double forecast = 0;
    for (const rig::TrialRecord& r : t.trials) {
      if (r.planned_reliability < kEdges[b] || r.planned_reliability >= kEdges[b + 1]) continue;
      ++n;
      reached += rig::reached_goal(r.outcome) ? 1 : 0;
      forecast += r.planned_reliability;
    }
    if (n == 0) continue;
    const rig::Interval w = rig::wilson_interval(reached, n);
    forecast /= static_cast<double>(n);
    std::cout << "  R in [" << kEdges[b] << ", " << kEdges[b + 1] << "): " << n << " journeys, forecast " << forecast
              << ", reached " << static_cast<double>(reached) / static_cast<double>(n) << " [" << w.low << ", "
              << w.high << "]" << (forecast < w.low || forecast > w.high ? " outside" : "") << "\n";
  }
}

// Published: 99.9% of 1,000 (docs/navigation-experiments.md, issue 17, third session: Far and Near
// descriptions); the level 99.5%: the bound lies at 99.4%, 1.9 points above the level less 2.
TEST(NavigationRates, SparseWorldWithAOneMillimetreSurvey) {
  expect_level_and_calibrated_forecast(trials_at(1.0, 1000), 0.995);
}

// Published: 97.6% of 2,000 (issue 17, fifth session: slides that know where their goal enters), the
// paper's survey error; the level 97%, issue 17's target (the bound at 96.8%; a fall to 95.5% puts it
// at 94.5%, under the level less 2).
TEST(NavigationRates, SparseWorldWithAOneAndAHalfMillimetreSurvey) {
  expect_level_and_calibrated_forecast(trials_at(1.5, 2000), 0.97);
}

// The dense world (400 marbles, `neopipe sim world --objects 400 --seed 1`), where the paper's
// descriptions reach 61% over five surveys: its crowded views are what Far and Near are for.
// Published: 99.7% of 1,000; the level 99% (the bound at 99.1%).
TEST(NavigationRates, DenseWorldWithAOneMillimetreSurvey) {
  expect_level_and_calibrated_forecast(trials_at(1.0, 1000, 400), 0.99);
}

}  // namespace
