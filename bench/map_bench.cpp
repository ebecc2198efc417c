// The map-maker's cost as the world grows (issue: 10,000 objects in under 1 s on one core): a world
// at the default density (100 marbles per 500 x 500 mm) is mapped whole (views, parkways and their
// reliable / detectable / recoverable sub-graphs, trajectories with their reliabilities) and one
// route planned across it with its custom map. Peer in the same run: the general parkways by
// checking every pair, O(n^2), which the grid avoids.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "nav/mapmaker/map_maker.hpp"
#include "nav/mapmaker/parkway_quality.hpp"
#include "nav/mapmaker/parkways.hpp"
#include "sim/world.hpp"

namespace {

namespace mm = neopipe::nav::mapmaker;

mm::Workspace world_of(int objects) {
  const double side = 500 * std::sqrt(objects / 100.0);
  const neopipe::sim::World w =
      neopipe::sim::generate_world({objects, {side, side}, 5.0, 3.0, static_cast<std::uint64_t>(objects)});
  return {w.size, w.objects};
}

// A far-apart pair the plan can join: the extremes along x + y of the largest strongly connected
// component of the step graph (a route between two of its objects always exists, since a step may
// adjust its landmark to any corner). Chosen once, outside the timed loop.
std::pair<std::uint32_t, std::uint32_t> far_reachable_pair(const mm::Workspace& workspace) {
  const mm::MapMaker maker(workspace, mm::MapMakerOptions{});
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const mm::Step& s : maker.steps().steps()) edges.emplace_back(s.from.object, s.landmark);
  const auto components = mm::strongly_connected_components(workspace.objects.size(), edges);
  const auto largest = std::max_element(components.begin(), components.end(),
                                        [](const auto& a, const auto& b) { return a.size() < b.size(); });
  std::uint32_t a = largest->front();
  std::uint32_t b = a;
  for (const std::uint32_t i : *largest) {
    if (workspace.objects[i].sum() < workspace.objects[a].sum()) a = i;
    if (workspace.objects[i].sum() > workspace.objects[b].sum()) b = i;
  }
  return {a, b};
}

void BM_MapWorldAndRoute(benchmark::State& state) {
  const mm::Workspace workspace = world_of(static_cast<int>(state.range(0)));
  const auto [a, b] = far_reachable_pair(workspace);
  std::size_t steps = 0;
  for (auto _ : state) {
    const mm::MapMaker maker(workspace, mm::MapMakerOptions{});
    const auto general = mm::general_parkways(maker.views());
    benchmark::DoNotOptimize(general.data());
    const auto qualities = mm::parkway_edge_qualities(maker.views(), maker.options().errors);
    benchmark::DoNotOptimize(qualities.data());
    steps = maker.plan(a, b, mm::CostCriterion::ratio).steps.size();
  }
  state.counters["objects"] = static_cast<double>(workspace.objects.size());
  state.counters["route_steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_MapWorldAndRoute)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// The map alone (views, steps with reliabilities, trajectories), and one route per criterion on it.
void BM_MapWorld(benchmark::State& state) {
  const mm::Workspace workspace = world_of(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const mm::MapMaker maker(workspace, mm::MapMakerOptions{});
    benchmark::DoNotOptimize(maker.steps().steps().data());
  }
}
BENCHMARK(BM_MapWorld)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_Route(benchmark::State& state) {
  const mm::Workspace workspace = world_of(10000);
  const auto [a, b] = far_reachable_pair(workspace);
  const mm::MapMaker maker(workspace, mm::MapMakerOptions{});
  const auto criterion = static_cast<mm::CostCriterion>(state.range(0));
  std::size_t steps = 0;
  for (auto _ : state) steps = maker.plan(a, b, criterion).steps.size();
  state.SetLabel(std::string(mm::criterion_name(criterion)));
  state.counters["route_steps"] = static_cast<double>(steps);
}
BENCHMARK(BM_Route)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// Peer: every pair checked for a shared window.
void BM_GeneralParkwaysAllPairs(benchmark::State& state) {
  const mm::Workspace workspace = world_of(static_cast<int>(state.range(0)));
  const neopipe::nav::WindowModel window;
  for (auto _ : state) {
    std::size_t edges = 0;
    const auto& o = workspace.objects;
    for (std::size_t i = 0; i < o.size(); ++i) {
      for (std::size_t j = i + 1; j < o.size(); ++j) edges += window.fit_together(o[i], o[j]) ? 1 : 0;
    }
    benchmark::DoNotOptimize(edges);
  }
}
BENCHMARK(BM_GeneralParkwaysAllPairs)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_GeneralParkwaysGrid(benchmark::State& state) {
  const mm::Workspace workspace = world_of(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const mm::WorldViews views(workspace, neopipe::nav::WindowModel{});
    benchmark::DoNotOptimize(mm::general_parkways(views).size());
  }
}
BENCHMARK(BM_GeneralParkwaysGrid)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
