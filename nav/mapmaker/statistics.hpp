#pragma once
// Parkway statistics (park-kender.md §3 "Statistics", §4; paper §4.3 Fig. 7 and §4.7 Fig. 11): random
// worlds of a given population, the number of parkways of each kind and of strongly connected
// components with and without trajectories, against the paper's Poisson estimate of how many objects
// found a new parkway. docs/parkway-statistics.md states the definitions and the formula.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "nav/common/window.hpp"
#include "nav/mapmaker/workspace.hpp"

namespace neopipe::nav::mapmaker {

/// What one world measures. Component counts include single-object components, as the paper's do
/// (a new object alone "forms a new parkway", Fig. 6; with no trajectories the SCC count "is equal to
/// the number of existing parkways", §4.7).
struct WorldCounts {
  double general_parkways = 0;       ///< connected components of "one window holds both"
  double multi_object_parkways = 0;  ///< of those, the ones with >= 2 objects
  double isolated_objects = 0;       ///< of those, the single objects
  double obvious_parkways = 0;       ///< strongly connected components of the obvious parkway
  double isolated_parkways = 0;      ///< SCCs of obvious + isolated edges (Fig. 11 without trajectories)
  double scc_with_trajectories = 0;  ///< SCCs of obvious + isolated + trajectory edges (Fig. 11)
  double obvious_edges = 0;
  double isolated_edges = 0;
  double trajectories = 0;
  double new_parkways = 0;  ///< objects that, added in order, saw no earlier object within one window (Fig. 6)
};

inline constexpr std::size_t kCountFields = 10;
/// The fields of WorldCounts in declaration order, with their CSV names.
std::array<std::string_view, kCountFields> count_names();
std::array<double, kCountFields> count_values(const WorldCounts& c);

/// Measures one world.
WorldCounts measure_world(const Workspace& workspace, const WindowModel& window);

/// Objects added one at a time, in order: how many had no earlier object that fits in one window
/// with it (each founds a new general parkway, paper Fig. 6). Linear time (a hash grid).
std::size_t count_new_parkways(const std::vector<Eigen::Vector2d>& objects, const WindowModel& window);

/// The paper's Poisson model: the object added to a world of t objects founds a new parkway with
/// probability exp(-4 A t / R), A = (a - 2m)^2 the square in which two objects share a window (the
/// paper's a^2, with m = 0), R = size^2. Expected new parkways after `population` objects: the sum over
/// t = 0 .. population-1.
double poisson_new_parkway_probability(double size, const WindowModel& window, std::size_t t);
double poisson_expected_new_parkways(double size, const WindowModel& window, std::size_t population);
/// The same model with each object's neighbourhood clipped to the world (not in the paper): an object
/// near an edge has less room for neighbours, so more objects found parkways. The expectation over
/// the new object's place is a midpoint sum on a 512 x 512 grid of the closed-form geometric sum.
double poisson_expected_new_parkways_bounded(double size, const WindowModel& window, std::size_t population);

/// The first `population` objects of trial `trial`'s world: uniform in the open square (0, size)^2,
/// from a generator seeded by (seed, trial) only. Worlds are nested (population N is the first N objects
/// of population N + 1, the paper's one-object-at-a-time process) and shared by every window size
/// (common random numbers make the comparison between windows sharper).
std::vector<Eigen::Vector2d> random_objects(double size, std::uint64_t seed, std::size_t trial, std::size_t population);

struct Summary {
  double mean = 0;
  double sd = 0;  ///< sample sd (n - 1); 0 with one trial
  double ci_low = 0;
  double ci_high = 0;  ///< mean -+ t(0.975, n-1) sd / sqrt(n)
};
/// Mean, sd and the 95% Student-t confidence interval of `values`.
Summary summarise(const std::vector<double>& values);
/// The two-sided 95% Student-t quantile t(0.975, dof); 1.96 for large dof.
double t_quantile_975(std::size_t dof);

struct StatisticsOptions {
  double size = 100;                     ///< world side r, mm
  std::vector<double> windows{5};        ///< window sides a, mm
  double margin_factor = 0.05;           ///< m = factor * a, as `neopipe map`
  std::vector<std::size_t> populations;  ///< N values
  std::size_t trials = 20;
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0: all
};

struct StatisticsRow {
  WindowModel window;
  std::size_t population = 0;
  std::size_t trials = 0;
  double density = 0;  ///< population (a - 2m)^2 / R: objects per window-reach square
  std::array<Summary, kCountFields> counts;
  double poisson_probability = 0;           ///< the next object founds a new parkway
  double poisson_new_parkways = 0;          ///< expected new parkways so far
  double poisson_new_parkways_bounded = 0;  ///< the same, neighbourhoods clipped to the world
};

/// Every (window, population) row, windows outer, populations inner, in the order given. Trials run
/// in parallel (oneTBB, `threads`); results are the same for every thread count. `progress` (may be
/// empty) is called with (worlds done, worlds in all), serialised, from any thread.
std::vector<StatisticsRow> parkway_statistics(const StatisticsOptions& options,
                                              const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace neopipe::nav::mapmaker
