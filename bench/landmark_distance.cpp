// neopipe_landmark_distance: context-based vs. landmark-based distance (park-kender.md §10, the
// paper's §7.2). For random reachable start/goal pairs of each world, plans the path of least window
// travel D (`--cost distance`) and the path of least landmark-based distance L (`--cost landmark`:
// straight lines between successive landmarks, whatever corner each is held at), and prints, as
// Markdown, both distances of both paths and what planning by L costs in real travel. The pairs are
// drawn as `neopipe nav --trials N --seed S` draws them (on the exact positions: the same pairs as
// with --sigma-map 0), so the same seed gives the same tables.
//
//   neopipe_landmark_distance --world w100.yaml --world w400.yaml [--pairs N] [--seed S]

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "nav/mapmaker/map_maker.hpp"
#include "rig/park_kender.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace {

namespace mm = neopipe::nav::mapmaker;

struct Options {
  std::vector<std::string> worlds;
  std::int64_t pairs = 1000;
  std::uint64_t seed = 1;
};

// The same pair planned both ways: by context-based distance D and by landmark-based distance L.
struct PairResult {
  mm::Route context;
  mm::Route landmark;
  // Both criteria break ties by D, so the same landmarks give the same path: a different map means
  // different landmarks, never only different corners.
  bool different_map() const { return context.custom_map != landmark.custom_map; }
  double excess_travel() const { return landmark.distance - context.distance; }
};

// The pairs `neopipe nav --trials --cost distance` would draw with this seed.
std::vector<PairResult> plan_pairs(const neopipe::rig::ParkKenderSystem& system, const Options& o) {
  std::vector<PairResult> out;
  const mm::MapMaker& maker = system.maker();
  for (const auto& plan : neopipe::rig::draw_plans(system, maker.workspace().objects.size(), o.pairs, o.seed)) {
    const mm::Route& r = neopipe::rig::route_of(*plan);
    out.push_back({r, maker.plan(r.start, r.goal, mm::CostCriterion::landmark)});
  }
  return out;
}

// Mean costs of both paths over a set of pairs.
struct Means {
  std::size_t pairs = 0;
  double context_d = 0, context_l = 0, context_u = 0;
  double landmark_d = 0, landmark_l = 0, landmark_u = 0;
  double context_steps = 0, landmark_steps = 0;
};

Means means_of(const std::vector<PairResult>& pairs) {
  Means m;
  m.pairs = pairs.size();
  for (const PairResult& p : pairs) {
    m.context_d += p.context.distance;
    m.context_l += p.context.landmark_distance;
    m.context_u += p.context.unreliability;
    m.landmark_d += p.landmark.distance;
    m.landmark_l += p.landmark.landmark_distance;
    m.landmark_u += p.landmark.unreliability;
    m.context_steps += static_cast<double>(p.context.steps.size());
    m.landmark_steps += static_cast<double>(p.landmark.steps.size());
  }
  const double n = pairs.empty() ? 1.0 : static_cast<double>(pairs.size());
  for (double* v : {&m.context_d, &m.context_l, &m.context_u, &m.landmark_d, &m.landmark_l, &m.landmark_u,
                    &m.context_steps, &m.landmark_steps})
    *v /= n;
  return m;
}

// The q-quantile (nearest rank) of `values`; 0 for none.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(std::lround(q * static_cast<double>(values.size() - 1)))];
}

// The landmark path's extra travel as a fraction of the context path's, for the pairs where the
// context path travels at all (D = 0 when the goal is in view from the start).
std::vector<double> relative_excess(const std::vector<PairResult>& pairs) {
  std::vector<double> out;
  for (const PairResult& p : pairs)
    if (p.context.distance > 0) out.push_back(p.excess_travel() / p.context.distance);
  return out;
}

struct WorldResult {
  std::string path;
  std::vector<PairResult> all;
  std::vector<PairResult> differ;  ///< the pairs whose two custom maps differ
};

WorldResult run_world(const std::string& path, const Options& o) {
  const neopipe::sim::World world = neopipe::sim::load_world(path);
  // The defaults of `neopipe map`: window 50 mm, sigma 1 mm (U only breaks ties of D and L here).
  const mm::MapMakerOptions options;
  neopipe::nav::navigator::NavigatorConfig navigator;
  navigator.window = options.window;
  const neopipe::rig::ParkKenderSystem system(mm::Workspace{world.size, world.objects}, options,
                                              mm::CostCriterion::distance, navigator);
  WorldResult r{path, plan_pairs(system, o), {}};
  std::copy_if(r.all.begin(), r.all.end(), std::back_inserter(r.differ),
               [](const PairResult& p) { return p.different_map(); });
  return r;
}

void print_means(const std::vector<WorldResult>& worlds) {
  fmt::print(
      "| world (pairs) | context path D | context path L | landmark path D | landmark path L | context path U | "
      "landmark path U | steps (context, landmark) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const WorldResult& w : worlds) {
    for (const auto& [label, pairs] : {std::pair{"all", &w.all}, std::pair{"paths differ", &w.differ}}) {
      const Means m = means_of(*pairs);
      fmt::print("| {}, {} ({}) | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.3f} | {:.3f} | {:.2f}, {:.2f} |\n", w.path,
                 label, m.pairs, m.context_d, m.context_l, m.landmark_d, m.landmark_l, m.context_u, m.landmark_u,
                 m.context_steps, m.landmark_steps);
    }
  }
}

void print_differences(const std::vector<WorldResult>& worlds) {
  fmt::print(
      "\n| world | paths differ | landmark path's extra D, all pairs | where they differ: extra D | median | 90th "
      "percentile | context path's extra L |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (const WorldResult& w : worlds) {
    const Means all = means_of(w.all), differ = means_of(w.differ);
    const std::vector<double> excess = relative_excess(w.differ);
    fmt::print(
        "| {} | {} of {} ({:.1f}%) | {:+.1f} mm ({:+.1f}%) | {:+.1f} mm ({:+.1f}%) | {:+.1f}% | {:+.1f}% | "
        "{:+.1f} mm ({:+.1f}%) |\n",
        w.path, w.differ.size(), w.all.size(),
        100 * static_cast<double>(w.differ.size()) / static_cast<double>(w.all.size()), all.landmark_d - all.context_d,
        100 * (all.landmark_d / all.context_d - 1), differ.landmark_d - differ.context_d,
        100 * (differ.landmark_d / differ.context_d - 1), 100 * quantile(excess, 0.5), 100 * quantile(excess, 0.9),
        differ.context_l - differ.landmark_l, 100 * (differ.context_l / differ.landmark_l - 1));
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Context-based vs. landmark-based distance over random reachable pairs; prints Markdown tables"};
  app.add_option("--world", o.worlds, "World file (neopipe sim world); repeat for several")->required();
  app.add_option("--pairs", o.pairs, "Reachable start/goal pairs per world")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100000000}));
  app.add_option("--seed", o.seed, "Seed of the pair draw (as neopipe nav --seed)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<WorldResult> worlds;
    for (const std::string& path : o.worlds) worlds.push_back(run_world(path, o));
    print_means(worlds);
    print_differences(worlds);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "neopipe_landmark_distance: {}\n", e.what());
    return 1;
  }
}
