#include "nav/mapmaker/statistics.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "nav/mapmaker/parkways.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {
namespace {

using Edges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// SplitMix64: a well-mixed, portable stream (std::uniform_real_distribution is not the same on every
// standard library, and results must be reproducible anywhere).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t state) : state_(state) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in the open interval (0, 1): objects never sit on the world's edge.
  double open_unit() { return (static_cast<double>(next() >> 12) + 0.5) * 0x1.0p-52; }

 private:
  std::uint64_t state_;
};

std::size_t scc_count(std::size_t nodes, const Edges& edges) {
  return strongly_connected_components(nodes, edges).size();
}

void add_edges(Edges& edges, const std::vector<ParkwayEdge>& parkway) {
  for (const ParkwayEdge& e : parkway) edges.emplace_back(e.from, e.to);
}

}  // namespace

std::array<std::string_view, kCountFields> count_names() {
  return {"general_parkways",      "multi_object_parkways", "isolated_objects", "obvious_parkways", "isolated_parkways",
          "scc_with_trajectories", "obvious_edges",         "isolated_edges",   "trajectories",     "new_parkways"};
}

std::array<double, kCountFields> count_values(const WorldCounts& c) {
  return {c.general_parkways,      c.multi_object_parkways, c.isolated_objects, c.obvious_parkways, c.isolated_parkways,
          c.scc_with_trajectories, c.obvious_edges,         c.isolated_edges,   c.trajectories,     c.new_parkways};
}

WorldCounts measure_world(const Workspace& workspace, const WindowModel& window) {
  WorldCounts c;
  const std::size_t n = workspace.objects.size();
  if (n == 0) return c;
  const WorldViews views(workspace, window);
  const auto general = general_parkways(views);
  c.general_parkways = static_cast<double>(general.size());
  c.isolated_objects =
      static_cast<double>(std::count_if(general.begin(), general.end(), [](const auto& g) { return g.size() == 1; }));
  c.multi_object_parkways = c.general_parkways - c.isolated_objects;

  const auto obvious = obvious_parkway(views);
  const auto isolated = isolated_parkway(views);
  c.obvious_edges = static_cast<double>(obvious.size());
  c.isolated_edges = static_cast<double>(isolated.size());
  Edges edges;
  add_edges(edges, obvious);
  c.obvious_parkways = static_cast<double>(scc_count(n, edges));
  // Obvious edges are isolated edges too (with one other object in view both descriptors pick it);
  // the union is kept so the count does not rest on that.
  add_edges(edges, isolated);
  c.isolated_parkways = static_cast<double>(scc_count(n, edges));
  const auto trajectories = all_trajectories(views);
  c.trajectories = static_cast<double>(trajectories.size());
  for (const Trajectory& t : trajectories) edges.emplace_back(t.from.object, t.to);
  c.scc_with_trajectories = static_cast<double>(scc_count(n, edges));
  c.new_parkways = static_cast<double>(count_new_parkways(workspace.objects, window));
  return c;
}

std::size_t count_new_parkways(const std::vector<Eigen::Vector2d>& objects, const WindowModel& window) {
  // Objects so far, bucketed in cells of side `reach`: an earlier object within reach lies in one of
  // the 3 x 3 cells around the new one. Linear in the population, so large populations stay cheap.
  const double reach = window.side - 2 * window.margin;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector2d>> cells;
  const auto key = [](std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
  };
  std::size_t founded = 0;
  for (const Eigen::Vector2d& q : objects) {
    const auto cx = static_cast<std::int64_t>(std::floor(q.x() / reach));
    const auto cy = static_cast<std::int64_t>(std::floor(q.y() / reach));
    bool seen = false;
    for (std::int64_t dx = -1; dx <= 1 && !seen; ++dx) {
      for (std::int64_t dy = -1; dy <= 1 && !seen; ++dy) {
        const auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        seen = std::any_of(it->second.begin(), it->second.end(),
                           [&](const Eigen::Vector2d& p) { return window.fit_together(p, q); });
      }
    }
    if (!seen) ++founded;
    cells[key(cx, cy)].push_back(q);
  }
  return founded;
}

double poisson_new_parkway_probability(double size, const WindowModel& window, std::size_t t) {
  const double reach = window.side - 2 * window.margin;
  return std::exp(-4 * reach * reach / (size * size) * static_cast<double>(t));
}

double poisson_expected_new_parkways(double size, const WindowModel& window, std::size_t population) {
  // Geometric sum of exp(-lambda t), t = 0 .. N-1; summed term by term: N is small and it stays exact
  // at lambda = 0.
  double sum = 0;
  for (std::size_t t = 0; t < population; ++t) sum += poisson_new_parkway_probability(size, window, t);
  return sum;
}

double poisson_expected_new_parkways_bounded(double size, const WindowModel& window, std::size_t population) {
  constexpr int kSteps = 512;
  const double reach = window.side - 2 * window.margin;
  // Length of the neighbourhood (x - reach, x + reach) inside (0, size), at each midpoint.
  std::vector<double> length(kSteps);
  for (int i = 0; i < kSteps; ++i) {
    const double x = (i + 0.5) * size / kSteps;
    length[static_cast<std::size_t>(i)] = std::min(x + reach, size) - std::max(x - reach, 0.0);
  }
  const double n = static_cast<double>(population);
  double sum = 0;
  for (const double lx : length) {
    for (const double ly : length) {
      // sum_{t<N} q^t = (1 - q^N) / (1 - q), with q = exp(-area / R); expm1 keeps it exact for tiny areas.
      const double rate = lx * ly / (size * size);
      sum += rate > 0 ? std::expm1(-rate * n) / std::expm1(-rate) : n;
    }
  }
  return sum / (static_cast<double>(kSteps) * kSteps);
}

std::vector<Eigen::Vector2d> random_objects(double size, std::uint64_t seed, std::size_t trial,
                                            std::size_t population) {
  // Seeds of nearby trials are decorrelated by running their combination through the mixer first.
  SplitMix64 mix(seed ^ (0xd1b54a32d192ed03ULL * (static_cast<std::uint64_t>(trial) + 1)));
  SplitMix64 rng(mix.next());
  std::vector<Eigen::Vector2d> objects(population);
  for (auto& p : objects) {
    const double x = rng.open_unit() * size;
    p = {x, rng.open_unit() * size};
  }
  return objects;
}

double t_quantile_975(std::size_t dof) {
  static constexpr std::array<double, 30> kTable{12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                                 2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                                 2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof == 0) return std::numeric_limits<double>::infinity();
  if (dof <= kTable.size()) return kTable[dof - 1];
  // Cornish-Fisher expansion around the normal quantile; error < 1e-4 beyond 30 degrees of freedom.
  const double z = 1.959963984540054;
  const double v = static_cast<double>(dof);
  const double z3 = z * z * z;
  const double z5 = z3 * z * z;
  return z + (z3 + z) / (4 * v) + (5 * z5 + 16 * z3 + 3 * z) / (96 * v * v);
}

Summary summarise(const std::vector<double>& values) {
  Summary s;
  if (values.empty()) return s;
  const double n = static_cast<double>(values.size());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  if (values.size() > 1) {
    double ss = 0;
    for (const double v : values) ss += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(ss / (n - 1));
  }
  // With one trial there is no spread to estimate: the interval collapses to the value rather than
  // being infinite, and the sd column (0) says so.
  const double half = values.size() > 1 ? t_quantile_975(values.size() - 1) * s.sd / std::sqrt(n) : 0;
  s.ci_low = s.mean - half;
  s.ci_high = s.mean + half;
  return s;
}

std::vector<StatisticsRow> parkway_statistics(const StatisticsOptions& o,
                                              const std::function<void(std::size_t, std::size_t)>& progress) {
  if (!(o.size > 0) || !std::isfinite(o.size)) throw MapError("world size must be positive");
  if (o.trials == 0) throw MapError("trials must be at least 1");
  std::vector<WindowModel> windows;
  for (const double a : o.windows) {
    if (!(a > 0) || !(a < o.size)) throw MapError("window sides must lie between 0 and the world size");
    windows.push_back({a, o.margin_factor * a});
  }
  const std::size_t per_window = o.populations.size() * o.trials;
  const std::size_t total = windows.size() * per_window;
  // One slot per world, written by whichever thread measures it and read back in index order, so
  // the sums (and so every digit of the CSV) do not depend on the schedule.
  std::vector<WorldCounts> measured(total);
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  const auto measure = [&](std::size_t index) {
    const std::size_t w = index / per_window;
    const std::size_t p = index % per_window / o.trials;
    const std::size_t trial = index % o.trials;
    const Workspace workspace{{o.size, o.size}, random_objects(o.size, o.seed, trial, o.populations[p])};
    measured[index] = measure_world(workspace, windows[w]);
    const std::size_t now = ++done;
    if (progress) {
      const std::lock_guard lock(progress_mutex);
      progress(now, total);
    }
  };
  // More threads than the machine has only makes TBB warn on stderr; the results do not depend on it.
  const int threads =
      o.threads > 0 ? std::min(o.threads, tbb::info::default_concurrency()) : tbb::task_arena::automatic;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) measure(i);
    });
  });

  std::vector<StatisticsRow> rows;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    for (std::size_t p = 0; p < o.populations.size(); ++p) {
      StatisticsRow row;
      row.window = windows[w];
      row.population = o.populations[p];
      row.trials = o.trials;
      const double reach = row.window.side - 2 * row.window.margin;
      row.density = static_cast<double>(row.population) * reach * reach / (o.size * o.size);
      for (std::size_t f = 0; f < kCountFields; ++f) {
        std::vector<double> values(o.trials);
        for (std::size_t t = 0; t < o.trials; ++t)
          values[t] = count_values(measured[w * per_window + p * o.trials + t])[f];
        row.counts[f] = summarise(values);
      }
      row.poisson_probability = poisson_new_parkway_probability(o.size, row.window, row.population);
      row.poisson_new_parkways = poisson_expected_new_parkways(o.size, row.window, row.population);
      row.poisson_new_parkways_bounded = poisson_expected_new_parkways_bounded(o.size, row.window, row.population);
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace neopipe::nav::mapmaker
