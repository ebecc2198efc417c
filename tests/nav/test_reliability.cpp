// Step reliabilities against their Monte Carlo definitions (park-kender.md §6): the fitted selection
// model against fresh simulations, the trajectory approximation against simulated slides.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "nav/common/landmarks.hpp"
#include "nav/mapmaker/reliability.hpp"
#include "nav/mapmaker/reliability_fit.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/view_agreement.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {
namespace {

// The fit's published maximum error over its 84 cells (docs/navigation.md).
constexpr double kPublishedMaxError = 0.024;

TEST(Reliability, FittedSelectionModelMatchesFreshMonteCarlo) {
  for (const int n : {3, 6, 10, 15}) {
    for (const double s : {0.01, 0.04, 0.12}) {
      constexpr int kTrials = 3000;
      const SelectionSample mc = simulate_selection(n, s, kTrials, 977 + static_cast<std::uint64_t>(n));
      const double model = selection_reliability(n, s * 50, 50);
      const double p = mc.reliability();
      const double tolerance = kPublishedMaxError + 3 * std::sqrt(p * (1 - p) / kTrials);
      EXPECT_NEAR(model, p, tolerance) << "n " << n << " sigma/a " << s;
    }
  }
}

TEST(Reliability, SelectionIsCertainWithOneCandidateOrNoErrorAndFallsWithRivalsAndError) {
  EXPECT_EQ(selection_reliability(1, 2.0, 50), 1.0);
  EXPECT_EQ(selection_reliability(2, 2.0, 50), 1.0);
  EXPECT_EQ(selection_reliability(8, 0.0, 50), 1.0);
  // With two in view the reference and the landmark are the only candidates, whatever the model's
  // coefficients (tests/mutation/mutants.json, N12: log(2 - 2) must not reach the formula).
  for (const double beta : {1.0, 0.0, -1.0}) {
    const SelectionReliabilityModel model{0.5, beta, 1.0};
    EXPECT_EQ(model(2, 0.05), 1.0) << "beta " << beta;
    EXPECT_EQ(model(1, 0.05), 1.0) << "beta " << beta;
  }
  for (int n = 3; n < 20; ++n) {
    EXPECT_LT(selection_reliability(n + 1, 1.0, 50), selection_reliability(n, 1.0, 50));
    EXPECT_LT(selection_reliability(n, 2.0, 50), selection_reliability(n, 1.0, 50));
    // Only sigma / a matters.
    EXPECT_DOUBLE_EQ(selection_reliability(n, 2.0, 100), selection_reliability(n, 1.0, 50));
  }
}

TEST(Reliability, FitRecoversTheCoefficientsOfExactSamples) {
  const SelectionReliabilityModel truth{0.3, 1.2, 0.9};
  std::vector<SelectionSample> samples;
  for (int n = 3; n <= 12; ++n)
    for (const double s : {0.01, 0.03, 0.1}) {
      constexpr int kTrials = 1'000'000'000;
      samples.push_back({n, s, kTrials, static_cast<int>(std::lround(truth(n, s) * kTrials))});
    }
  const SelectionFit fit = fit_selection(samples);
  EXPECT_NEAR(fit.model.log_k, truth.log_k, 1e-5);
  EXPECT_NEAR(fit.model.beta, truth.beta, 1e-5);
  EXPECT_NEAR(fit.model.gamma, truth.gamma, 1e-5);
  EXPECT_LT(fit.max_error, 1e-6);
  EXPECT_THROW(fit_selection(std::span<const SelectionSample>(samples.data(), 2)), std::invalid_argument);
}

// A world at the simulator's default density (200 marbles in 700 x 700 mm), built here so the test
// does not depend on the simulator.
Workspace random_world(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(5, 695);
  Workspace w{{700, 700}, {}};
  while (w.objects.size() < 200) {
    const Eigen::Vector2d p(unit(rng), unit(rng));
    bool clear = true;
    for (const Eigen::Vector2d& q : w.objects) clear = clear && (p - q).norm() >= 6;
    if (clear) w.objects.push_back(p);
  }
  return w;
}

TEST(Reliability, TrajectoryApproximationAgreesWithMonteCarloOnAverage) {
  const Workspace workspace = random_world(11);
  const WorldViews views(workspace, WindowModel{});
  const std::vector<Trajectory> all = all_trajectories(views);
  ASSERT_GT(all.size(), 300u);
  for (const double sigma : {0.5, 2.0}) {
    NavigatorErrors errors;
    errors.sigma = sigma;
    double sum_abs = 0, bias = 0;
    int count = 0;
    for (std::size_t i = 0; i < all.size(); i += 5) {
      const double mc = simulate_trajectory(views, all[i], errors, 400, 5 + i);
      const double an = trajectory_reliability(views, all[i], errors);
      ASSERT_GE(an, 0.0);
      ASSERT_LE(an, 1.0);
      sum_abs += std::abs(an - mc);
      bias += an - mc;
      ++count;
    }
    std::cout << "sigma " << sigma << ": mean |analytic - Monte Carlo| " << sum_abs / count << ", bias " << bias / count
              << "\n";
    // With every object's own survey error in both (issue 17), the window moving with the reference
    // and the rivals found on the real entry distances: mean |diff| 0.054 at sigma 2 (bias -0.009),
    // part of it the Monte Carlo's own noise (400 draws: sd up to 0.025 per trajectory).
    EXPECT_LT(sum_abs / count, 0.025 + 0.03 * sigma) << "sigma " << sigma;
    EXPECT_LT(std::abs(bias / count), 0.02) << "sigma " << sigma;
  }
}

TEST(Reliability, TrajectoriesAreCertainWithoutErrorsAndLessSoWithMore) {
  const Workspace workspace = random_world(12);
  const WorldViews views(workspace, WindowModel{});
  const std::vector<Trajectory> all = all_trajectories(views);
  double previous = 0;
  for (const double sigma : {0.0, 0.5, 1.0, 2.0, 4.0}) {
    NavigatorErrors errors;
    errors.sigma = sigma;
    errors.translation_per_mm = 0;
    errors.rotation_per_mm = 0;
    double mean = 0;
    for (const Trajectory& t : all) {
      const double r = trajectory_reliability(views, t, errors);
      if (sigma == 0) {
        EXPECT_EQ(r, 1.0);
      }
      mean += r;
    }
    mean /= static_cast<double>(all.size());
    if (sigma > 0) {
      EXPECT_LT(mean, previous) << "sigma " << sigma;
    }
    previous = mean;
  }
}

// w400's 391 -> 120 rebuilt: the reference held at NE sees one other object, which gives the
// direction; sliding along it, the goal and a second marble enter by the window's bottom edge 0.03 mm
// of depth apart. No offset or turn of the slide changes their order, but the navigator's own
// measurements of the two do: the step must not be rated certain. Three millimetres apart it is.
TEST(Reliability, TwoMarblesEnteringByTheSameEdgeAlmostTogetherAreACoinToss) {
  const auto rate = [](double competitor_y) {
    const Workspace w{{400, 400}, {{200, 200}, {171.6, 195.46}, {160.15, 150.88}, {187.3, competitor_y}, {330, 330}}};
    const WorldViews views(w, WindowModel::with_side(50));
    const auto t = trajectory_from(views, {0, Corner::NE}, Description::Obvious, Direction::positive);
    EXPECT_TRUE(t.has_value());
    if (!t) return -1.0;
    EXPECT_EQ(t->to, 2U);  // the goal enters first
    // The slide's geometry alone is sure of the order; the navigator's measurements are not.
    NavigatorErrors errors;
    errors.sigma = 0.2;
    errors.rotation_per_mm = 0;
    EXPECT_GT(trajectory_reliability(views, *t, errors), 0.99);
    return entry_order_agreement(views, *t, 0.2);
  };
  const double close = rate(150.85);
  const double apart = rate(147.85);
  EXPECT_GT(close, 0.25);  // 0.03 mm of depth against sqrt(2) * 0.2 mm: about 0.54 less the lag's slant
  EXPECT_LT(close, 0.7);
  EXPECT_GT(apart, 0.95);
}

}  // namespace
}  // namespace neopipe::nav::mapmaker

namespace neopipe::nav::mapmaker {
namespace {

// Object 0 held at `corner` slides along the line to the obvious object 1 (or back); object 2 must
// be the goal. The analytic R and a Monte Carlo that moves every object by its own error and holds
// the reference where it really is (20,000 draws).
struct Rated {
  double analytic = -1;
  double simulated = -1;
};
Rated rate_trajectory(const Workspace& w, Corner corner, Direction direction, const NavigatorErrors& errors) {
  const WorldViews views(w, WindowModel::with_side(50));
  const auto t = trajectory_from(views, {0, corner}, Description::Obvious, direction);
  EXPECT_TRUE(t.has_value());
  if (!t) return {};
  EXPECT_EQ(t->via, 1U);
  EXPECT_EQ(t->to, 2U);
  return {trajectory_reliability(views, *t, errors), simulate_trajectory(views, *t, errors, 20000, 7)};
}

// Issue 17: every object lies off its surveyed place by its own error, and the model must price
// one that lies just outside the swept band: with it the analytic R agrees with a Monte Carlo that
// moves every object (the model that moved the reference and the direction landmark only rated an
// object 3 mm outside as far less likely to enter).
TEST(Reliability, AnObjectJustOutsideTheSweptBandIsPricedByItsOwnError) {
  const auto check = [](double distractor_y) {
    // Reference at (100, 100) held at SW, the direction landmark due East in view: the window slides
    // East over y in [97.5, 147.5]; the goal lies ahead inside, the distractor beside the band.
    const Workspace w{{400, 300}, {{100, 100}, {140, 100}, {260, 120}, {200, distractor_y}}};
    NavigatorErrors errors;
    errors.translation_per_mm = 0;
    errors.rotation_per_mm = 0;
    errors.sigma = 0;
    EXPECT_EQ(rate_trajectory(w, Corner::SW, Direction::positive, errors).analytic, 1.0);
    errors.sigma = 1.5;
    const Rated r = rate_trajectory(w, Corner::SW, Direction::positive, errors);
    EXPECT_NEAR(r.analytic, r.simulated, 0.03) << "distractor at y " << distractor_y;
    return r.analytic;
  };
  const double near = check(150.5);  // 3 mm outside the band
  const double far = check(165.5);   // 18 mm outside
  EXPECT_LT(near, 0.8);
  EXPECT_GT(far, 0.98);
}

// Issue 17, second session: two trajectories rebuilt from surveys where the navigator failed far
// more often than the map-maker forecast (both held at SE, sliding away from the landmark: Trajn).
Rated rebuilt(const Workspace& w, double sigma) {
  NavigatorErrors errors;
  errors.sigma = sigma;
  return rate_trajectory(w, Corner::SE, Direction::negative, errors);
}

// Sliding away from the direction's landmark (Trajn), the reference's error moves the window and
// turns the track the same way: the two add up. The goal enters by the bottom edge 19 mm of slide
// before a rival enters by the right one; the model that let them cancel rated it 0.993.
TEST(Reliability, OnTrajnTheReferencesErrorAndTheTurnItCausesAddUp) {
  const Workspace w{{400, 300},
                    {{200, 150},
                     {171.71, 160.36},
                     {217.59, 138.62},
                     {242.34, 154.02},
                     {204.93, 220.07},
                     {144.30, 178.60},
                     {273.38, 119.14},
                     {247.99, 84.29}}};
  const Rated r = rebuilt(w, 1.5);
  EXPECT_NEAR(r.analytic, r.simulated, 0.03);
  EXPECT_LT(r.analytic, 0.93);
  EXPECT_GT(r.analytic, 0.85);
}

// A marble that the surveyed slide passes just beyond the window's trailing corner enters by the
// bottom edge, before the goal, when the window is a little off: 34% of the time at sigma 1. The
// linearised model took it for an object beside the band that never enters (R 1.000).
TEST(Reliability, AMarbleSkimmingTheTrailingCornerIsARival) {
  const Workspace w{{400, 300},
                    {{200, 150},
                     {159.91, 155.54},
                     {248.65, 174.64},
                     {205.96, 140.06},
                     {206.62, 110.11},
                     {235.41, 123.52},
                     {257.41, 147.78}}};
  const Rated r = rebuilt(w, 1.0);
  EXPECT_NEAR(r.analytic, r.simulated, 0.03);
  EXPECT_LT(r.analytic, 0.75);
}

// Far and Near by their definition: every object's place off by sigma per axis, the window held at
// the reference's measured corner, the description run on what is then in view; the step holds when
// it picks the object it picks on the survey.
double simulated_distance_rank(const Workspace& w, const Placement& from, Description description, double sigma,
                               std::uint32_t expected, int trials) {
  const WindowModel window = WindowModel::with_side(50);
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0, sigma);
  int held = 0;
  for (int t = 0; t < trials; ++t) {
    std::vector<Eigen::Vector2d> seen;
    std::vector<std::uint32_t> ids;
    std::vector<Eigen::Vector2d> moved;
    for (const Eigen::Vector2d& p : w.objects) moved.emplace_back(p.x() + noise(rng), p.y() + noise(rng));
    const Eigen::Vector2d origin = window.origin(moved[from.object], from.corner);
    std::size_t reference = 0;
    for (std::uint32_t i = 0; i < moved.size(); ++i) {
      if (i != from.object && !window.sees(origin, moved[i])) continue;
      if (i == from.object) reference = seen.size();
      seen.push_back(moved[i]);
      ids.push_back(i);
    }
    const auto pick = select_landmark(description, {seen, reference});
    held += pick && ids[*pick] == expected ? 1 : 0;
  }
  return static_cast<double>(held) / trials;
}

// The reference at (100, 100) held at SW: the window spans [97.5, 147.5] on both axes. Near's
// landmark has a rival 1.2 mm farther inside and one 0.7 mm outside the left edge but nearer, which
// takes its place whenever the errors bring it in; Far's has a rival 7 mm nearer inside and one
// 2.5 mm outside the top edge but farther.
TEST(Reliability, FarAndNearRanksAgreeWithMonteCarlo) {
  const Workspace w{{400, 300}, {{100, 100}, {110, 104}, {104, 111}, {96.8, 103}, {140, 140}, {145, 120}, {150, 150}}};
  const WorldViews views(w, WindowModel::with_side(50));
  const Placement from{0, Corner::SW};
  ASSERT_EQ(views.landmark(from, Description::Near), 1u);
  ASSERT_EQ(views.landmark(from, Description::Far), 4u);
  EXPECT_EQ(distance_rank_reliability(views, from, Description::Near, 0), 1.0);
  for (const double sigma : {0.5, 1.0, 1.5}) {
    const double near = distance_rank_reliability(views, from, Description::Near, sigma);
    const double far = distance_rank_reliability(views, from, Description::Far, sigma);
    const double near_sim = simulated_distance_rank(w, from, Description::Near, sigma, 1, 20000);
    const double far_sim = simulated_distance_rank(w, from, Description::Far, sigma, 4, 20000);
    std::cout << "sigma " << sigma << ": Near " << near << " (simulated " << near_sim << "), Far " << far
              << " (simulated " << far_sim << ")\n";
    // 20,000 trials: the simulated rates are good to 0.004 (1 sd); the model that took the rivals as
    // independent, blind to the reference's error they share, was 0.03 too low.
    EXPECT_NEAR(near, near_sim, 0.012) << sigma;
    EXPECT_NEAR(far, far_sim, 0.012) << sigma;
  }
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
