// neopipe_navigator_sensitivity: how much the navigator's fixed constants matter (issue 17). For
// each constant of NavigatorConfig that is neither configuration nor derived from it, runs the same
// journeys (`neopipe nav --trials N --sigma-map S --seed 1` on the world) with the constant halved
// and doubled, and prints, as Markdown, the share reaching the goal against the default with the
// paired counts and the exact McNemar test. The map-maker is the same in every row: only the
// navigator changes.
//
//   neopipe_navigator_sensitivity --world w100.yaml [--trials 400] [--sigma-map 1] [--seed 1]

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "rig/experiment.hpp"
#include "rig/outcome.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace {

namespace rig = neopipe::rig;
namespace mm = neopipe::nav::mapmaker;
namespace nv = neopipe::nav::navigator;

struct Constant {
  std::string name;
  std::function<void(nv::NavigatorConfig&, double)> scale;
  std::string value;
};

std::vector<Constant> constants(const nv::NavigatorConfig& c) {
  return {
      {"adjust tolerance", [](nv::NavigatorConfig& n, double k) { n.adjust_tolerance *= k; },
       fmt::format("{} mm", c.adjust_tolerance)},
      {"position sd of a marble", [](nv::NavigatorConfig& n, double k) { n.position_sigma *= k; },
       fmt::format("{} mm", c.position_sigma)},
      {"turn sd per move", [](nv::NavigatorConfig& n, double k) { n.turn_sigma0 *= k; }, "0.05 deg"},
      {"view margin", [](nv::NavigatorConfig& n, double k) { n.view_margin *= k; },
       fmt::format("{:.2f} mm", c.view_margin)},
      {"slide step", [](nv::NavigatorConfig& n, double k) { n.slide_step *= k; }, fmt::format("{} mm", c.slide_step)},
      {"slide offset", [](nv::NavigatorConfig& n, double k) { n.slide_offset *= k; },
       fmt::format("{:.1f} mm", c.slide_offset)},
      {"candidates per entry",
       [](nv::NavigatorConfig& n, double k) { n.max_alternatives = static_cast<int>(n.max_alternatives * k); },
       fmt::format("{}", c.max_alternatives)},
      {"returns per journey",
       [](nv::NavigatorConfig& n, double k) { n.max_backtracks = static_cast<int>(n.max_backtracks * k); },
       fmt::format("{}", c.max_backtracks)},
  };
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"How much each fixed constant of the navigator matters: halved and doubled, on the same journeys"};
  std::string world_path;
  std::int64_t trials = 400;
  double sigma = 1;
  std::uint64_t seed = 1;
  app.add_option("--world", world_path, "World file (neopipe sim world)")->required();
  app.add_option("--trials", trials, "Journeys per row")->capture_default_str();
  app.add_option("--sigma-map", sigma, "Gaussian survey error, mm")->capture_default_str();
  app.add_option("--seed", seed, "As neopipe nav --seed")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const neopipe::sim::World world = neopipe::sim::load_world(world_path);
    const rig::Survey survey = rig::gaussian_survey(world, sigma, seed);
    rig::ExperimentConfig config;
    config.seed = seed;
    const rig::ExperimentSettings base = rig::derive_settings(config, survey.sigma);
    const auto run = [&](const nv::NavigatorConfig& navigator) {
      rig::ExperimentSettings s = base;
      s.navigator = navigator;
      const auto system = rig::make_park_kender(survey, s, mm::CostCriterion::reliability);
      const auto plans = rig::draw_plans(*system, world.objects.size(), trials, seed);
      return rig::run_trials(*system, plans, world, s.journey, 0);
    };
    const rig::TrialsSummary reference = run(base.navigator);
    const auto pct = [](const rig::TrialsSummary& t) {
      return 100.0 * static_cast<double>(t.reached()) / static_cast<double>(t.run());
    };
    std::cout << fmt::format("{} journeys on {}, --sigma-map {}, --seed {}: {:.1f}% with every constant as it is\n\n",
                             trials, world_path, sigma, seed, pct(reference));
    std::cout << "| constant | value | halved | halved only / default only | p | doubled | doubled only / default "
                 "only | p |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Constant& c : constants(base.navigator)) {
      std::string row = fmt::format("| {} | {} |", c.name, c.value);
      for (const double k : {0.5, 2.0}) {
        nv::NavigatorConfig n = base.navigator;
        c.scale(n, k);
        const rig::TrialsSummary t = run(n);
        const rig::PairedComparison p = rig::compare_paired(t, reference);
        row += fmt::format(" {:.1f}% | {} / {} | {:.2g} |", pct(t), p.a_only, p.b_only, p.p_value);
      }
      std::cout << row << '\n' << std::flush;
    }
  } catch (const std::exception& e) {
    std::cerr << "neopipe_navigator_sensitivity: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
