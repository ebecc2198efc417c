// View agreement: a hand-made borderline view, and the factor against a Monte Carlo simulation of
// the navigator's view on random worlds.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "nav/mapmaker/view_agreement.hpp"
#include "tests/nav/uniform_world.hpp"

namespace neopipe::nav::mapmaker {
namespace {

using test_worlds::uniform_world;

double normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

TEST(ViewAgreement, AnObjectJustOutsideSpoilsAnObviousView) {
  // Reference 0 held at SW: window [97.5, 147.5]^2. Object 1 well inside, object 2 one mm beyond
  // the east edge: if it slips in, the navigator sees two candidates and Obvious fails.
  const Workspace w{{300, 300}, {{100, 100}, {120, 130}, {148.5, 120}}};
  const WorldViews views(w, WindowModel::with_side(50));
  const Placement sw{0, Corner::SW};
  ASSERT_EQ(views.obvious(sw), 1U);
  EXPECT_NEAR(view_agreement(views, sw, Description::Obvious, 1.0), normal_cdf(1.0 / std::numbers::sqrt2), 1e-12);
  EXPECT_EQ(view_agreement(views, sw, Description::Obvious, 0.0), 1.0);
  // With a tiny sigma the edge is many deviations away.
  EXPECT_NEAR(view_agreement(views, sw, Description::Obvious, 0.01), 1.0, 1e-12);
  // Far from every edge: nothing can flip.
  const Workspace calm{{300, 300}, {{100, 100}, {120, 130}, {250, 250}}};
  const WorldViews calm_views(calm, WindowModel::with_side(50));
  EXPECT_EQ(view_agreement(calm_views, sw, Description::Obvious, 1.0), 1.0);
}

// The navigator's view, simulated: every position perturbed by N(0, sigma^2) per axis, the window
// placed from the perturbed reference; the selection made on what is then in view.
double simulated_agreement(const WorldViews& views, const Placement& from, Description description, double sigma,
                           int trials, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  const auto predicted = views.landmark(from, description);
  const WindowModel& window = views.window();
  // Only objects near the window can matter.
  std::vector<std::uint32_t> near;
  const Eigen::Vector2d origin = views.origin(from);
  const Eigen::Vector2d widen(20 * sigma + 1, 20 * sigma + 1);
  views.grid().for_each_near(origin - widen, origin + Eigen::Vector2d(window.side, window.side) + widen,
                             [&](std::uint32_t id) { near.push_back(id); });
  std::sort(near.begin(), near.end());
  int agree = 0;
  for (int t = 0; t < trials; ++t) {
    std::vector<Eigen::Vector2d> seen_points;
    std::vector<std::uint32_t> seen_ids;
    std::vector<Eigen::Vector2d> moved;
    for (const std::uint32_t id : near) moved.push_back(views.position(id) + Eigen::Vector2d(noise(rng), noise(rng)));
    const std::size_t ref = std::find(near.begin(), near.end(), from.object) - near.begin();
    const Eigen::Vector2d o = window.origin(moved[ref], from.corner);
    std::size_t reference = 0;
    for (std::size_t i = 0; i < near.size(); ++i) {
      if (i != ref && !window.sees(o, moved[i])) continue;
      if (i == ref) reference = seen_ids.size();
      seen_ids.push_back(near[i]);
      seen_points.push_back(views.position(near[i]));  // true positions: only the view is simulated
    }
    const auto chosen = select_landmark(description, View{seen_points, reference});
    const auto got = chosen ? std::optional<std::uint32_t>(seen_ids[*chosen]) : std::nullopt;
    agree += got == predicted ? 1 : 0;
  }
  return static_cast<double>(agree) / trials;
}

void check_against_simulation(const Workspace& w, double sigma) {
  const WorldViews views(w, WindowModel::with_side(50));
  double sum_abs = 0, sum_model = 0, sum_sim = 0;
  int placements = 0, borderline = 0;
  for (std::uint32_t node = 0; node < 4 * w.objects.size(); node += 3) {
    const Placement p = Placement::of_node(node);
    const Description d = views.obvious(p) ? Description::Obvious : Description::Isol;
    if (!views.landmark(p, d)) continue;
    const double model = view_agreement(views, p, d, sigma);
    const double sim = simulated_agreement(views, p, d, sigma, 400, node);
    sum_abs += std::abs(model - sim);
    sum_model += model;
    sum_sim += sim;
    borderline += model < 0.99 ? 1 : 0;
    ++placements;
  }
  ASSERT_GT(placements, 100);
  EXPECT_GT(borderline, 10);  // enough borderline views for the comparison to mean something
  std::cout << "mean |model - simulated| " << sum_abs / placements << ", mean model " << sum_model / placements
            << ", mean simulated " << sum_sim / placements << ", borderline " << borderline << "/" << placements
            << "\n";
  // The model treats the flips as independent, but all offsets share the reference's error; it is
  // close on average and slightly pessimistic.
  EXPECT_LT(sum_abs / placements, 0.04);
  EXPECT_NEAR(sum_model / placements, sum_sim / placements, 0.02);
}

TEST(ViewAgreement, MatchesASimulatedNavigatorOnRandomWorlds) {
  // The default density (100 marbles per 500 x 500 mm) and a dense world, at the default sigma.
  for (const auto& [n, side] : {std::pair{200, 700.0}, std::pair{300, 400.0}}) {
    check_against_simulation(uniform_world(n, side, 21), 1.0);
  }
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
