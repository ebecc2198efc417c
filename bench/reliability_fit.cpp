// neopipe_reliability_fit: the Monte Carlo runs behind the step reliabilities (docs/navigation.md,
// "Reliability"). Prints, as Markdown: the selection reliability estimated for n = 3..16 objects in
// view and sigma / a from 0.005 to 0.16, the fitted model with its errors (paste the coefficients
// into nav/mapmaker/reliability.cpp), and the trajectory approximation against Monte Carlo on random
// worlds at the default density.
//
//   neopipe_reliability_fit [--trials N] [--seed S] [--worlds W]

#include "nav/mapmaker/reliability_fit.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nav/mapmaker/trajectories.hpp"
#include "sim/world.hpp"

namespace {

namespace mm = neopipe::nav::mapmaker;

struct Options {
  int trials = 4000;
  std::uint64_t seed = 1;
  int worlds = 4;
};

void selection_table(const Options& o) {
  const std::vector<double> sigmas{0.005, 0.01, 0.02, 0.04, 0.08, 0.16};
  std::vector<mm::SelectionSample> samples;
  fmt::print("## Isolated-landmark selection: Monte Carlo R(n, sigma/a), {} trials per cell\n\n| n |", o.trials);
  for (const double s : sigmas) fmt::print(" {} |", s);
  fmt::print("\n|---|");
  for (std::size_t k = 0; k < sigmas.size(); ++k) fmt::print("---|");
  fmt::print("\n");
  for (int n = 3; n <= 16; ++n) {
    fmt::print("| {} |", n);
    for (std::size_t k = 0; k < sigmas.size(); ++k) {
      const auto s =
          mm::simulate_selection(n, sigmas[k], o.trials, o.seed * 1000 + static_cast<std::uint64_t>(n * 16) + k);
      samples.push_back(s);
      fmt::print(" {:.3f} |", s.reliability());
    }
    fmt::print("\n");
  }
  const mm::SelectionFit fit = mm::fit_selection(samples);
  fmt::print(
      "\nFit R = 1 / (1 + exp(log_k) (n - 2)^beta (sigma/a)^gamma): log_k = {:.6f}, beta = {:.6f}, gamma = {:.6f}\n"
      "Fit error over the {} cells: RMS {:.4f}, max {:.4f}\n\n",
      fit.model.log_k, fit.model.beta, fit.model.gamma, samples.size(), fit.rms_error, fit.max_error);
}

void trajectory_check(const Options& o) {
  fmt::print("## Trajectories: analytic approximation vs Monte Carlo ({} trials each)\n\n", o.trials / 10);
  fmt::print("| sigma mm | trajectories | mean MC R | mean analytic R | mean abs diff | max abs diff | bias |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  for (const double sigma : {0.25, 1.0, 4.0}) {
    mm::NavigatorErrors errors;
    errors.sigma = sigma;
    double sum_mc = 0, sum_an = 0, sum_abs = 0, max_abs = 0;
    int count = 0;
    for (int w = 0; w < o.worlds; ++w) {
      const auto world =
          neopipe::sim::generate_world({200, {700, 700}, 5.0, 3.0, o.seed + static_cast<std::uint64_t>(w)});
      const mm::Workspace workspace{world.size, world.objects};
      const mm::WorldViews views(workspace, neopipe::nav::WindowModel{});
      const std::vector<mm::Trajectory> all = mm::all_trajectories(views);
      for (std::size_t i = 0; i < all.size(); i += 7) {
        const double mc = mm::simulate_trajectory(views, all[i], errors, o.trials / 10, o.seed + i);
        const double an = mm::trajectory_reliability(views, all[i], errors);
        sum_mc += mc;
        sum_an += an;
        sum_abs += std::abs(an - mc);
        max_abs = std::max(max_abs, std::abs(an - mc));
        ++count;
      }
    }
    fmt::print("| {} | {} | {:.4f} | {:.4f} | {:.4f} | {:.4f} | {:+.4f} |\n", sigma, count, sum_mc / count,
               sum_an / count, sum_abs / count, max_abs, (sum_an - sum_mc) / count);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Monte Carlo runs behind the map-maker's step reliabilities; prints Markdown tables"};
  app.add_option("--trials", o.trials, "Trials per selection cell (a tenth of it per trajectory)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  app.add_option("--seed", o.seed, "Random seed: the same seed gives the same tables")->capture_default_str();
  app.add_option("--worlds", o.worlds, "Random worlds for the trajectory check")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  CLI11_PARSE(app, argc, argv);
  try {
    selection_table(o);
    trajectory_check(o);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "neopipe_reliability_fit: {}\n", e.what());
    return 1;
  }
}
