// The qualitative relational map's update cost (issue 20: one measurement fused into a 30-landmark
// map in under 1 ms on average; spec qrm.md §10's M5). A world of 30 landmarks uniform in a square,
// 50 imaging positions, the 18 nearest landmarks of each, every triple of them measured from exact
// bearings and ranges (spec §6, testing only the states still open in the map) and fused in order.
// The measurements are computed once, outside the timing, by running the same sequence; each
// iteration fuses them into a fresh map, which then evolves exactly as in that run.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "nav/qrm/edc.hpp"
#include "nav/qrm/measurement.hpp"
#include "nav/qrm/relational_map.hpp"

namespace {

namespace qrm = neopipe::nav::qrm;

struct Measurement {
  qrm::LandmarkId a, b, c;
  qrm::StateSet states;
};

std::vector<Eigen::Vector2d> landmarks(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0, 500);
  for (;;) {
    std::vector<Eigen::Vector2d> p;
    p.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
    if (!qrm::first_degenerate_triple(p)) return p;
  }
}

// The run whose measurements the benchmark replays.
std::vector<Measurement> run(int n, int images, int k, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::vector<Eigen::Vector2d> p = landmarks(rng, n);
  std::uniform_real_distribution<double> u(0, 500);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  qrm::RelationalMap map;
  for (int i = 0; i < n; ++i) map.add_landmark(static_cast<qrm::LandmarkId>(i));
  std::vector<Measurement> out;
  for (int image = 0; image < images; ++image) {
    const Eigen::Vector2d camera{u(rng), u(rng)};
    const double zero = turn(rng);
    std::vector<qrm::LandmarkId> seen(n);
    for (int i = 0; i < n; ++i) seen[i] = static_cast<qrm::LandmarkId>(i);
    std::sort(seen.begin(), seen.end(), [&](qrm::LandmarkId x, qrm::LandmarkId y) {
      return (p[x] - camera).squaredNorm() < (p[y] - camera).squaredNorm();
    });
    seen.resize(std::min(k, n));
    std::sort(seen.begin(), seen.end());
    const auto sighting = [&](qrm::LandmarkId i) {
      const Eigen::Vector2d v = p[i] - camera;
      return qrm::Sighting{std::atan2(v.y(), v.x()) - zero, v.norm()};
    };
    for (std::size_t x = 0; x < seen.size(); ++x) {
      for (std::size_t y = x + 1; y < seen.size(); ++y) {
        for (std::size_t z = y + 1; z < seen.size(); ++z) {
          const qrm::LandmarkId a = seen[x];
          const qrm::LandmarkId b = seen[y];
          const qrm::LandmarkId c = seen[z];
          const qrm::StateSet m = qrm::measure({sighting(a), sighting(b), sighting(c)}, map.relation(a, b, c));
          map.fuse(a, b, c, m);
          out.push_back({a, b, c, m});
        }
      }
    }
  }
  return out;
}

void BM_FuseMeasurement(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::vector<Measurement> sequence = run(n, 50, 18, 1);
  int inconsistencies = 0;
  double total = 0;
  std::int64_t runs = 0;
  for (auto _ : state) {
    qrm::RelationalMap map;
    for (int i = 0; i < n; ++i) map.add_landmark(static_cast<qrm::LandmarkId>(i));
    const auto start = std::chrono::steady_clock::now();
    for (const Measurement& m : sequence) map.fuse(m.a, m.b, m.c, m.states);
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(took.count());
    total += took.count();
    ++runs;
    inconsistencies = map.inconsistencies();
  }
  state.counters["measurements"] = static_cast<double>(sequence.size());
  state.counters["us_per_measurement"] = 1e6 * total / static_cast<double>(runs * sequence.size());
  state.counters["inconsistencies"] = inconsistencies;
}
BENCHMARK(BM_FuseMeasurement)->Arg(30)->UseManualTime()->Unit(benchmark::kMillisecond);

// One measurement of a triple with all 20 states open (the first image's cost), from random scenes.
void BM_MeasureTriple(benchmark::State& state) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 500);
  std::vector<std::array<qrm::Sighting, 3>> scenes;
  for (int n = 0; n < 64; ++n) {
    const Eigen::Vector2d camera{u(rng), u(rng)};
    std::array<qrm::Sighting, 3> s;
    for (auto& x : s) {
      const Eigen::Vector2d v = Eigen::Vector2d(u(rng), u(rng)) - camera;
      x = {std::atan2(v.y(), v.x()), v.norm()};
    }
    scenes.push_back(s);
  }
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(qrm::measure(scenes[i++ % scenes.size()], qrm::StateSet::all()));
}
BENCHMARK(BM_MeasureTriple)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
