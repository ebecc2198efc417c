#include "apps/compare_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/cli_support.hpp"
#include "apps/compare_plot.hpp"
#include "apps/progress.hpp"
#include "rig/comparison.hpp"
#include "rig/contenders.hpp"

namespace neopipe::apps {
namespace {

rig::ContendersRequest contenders_request(const CompareArgs& a) {
  rig::ContendersRequest r;
  r.nav.world = a.world;
  r.nav.cost = a.cost;
  r.nav.sigma_map = a.sigma_map;
  r.nav.realism = a.realism;
  r.nav.sigma_move = a.sigma_move;
  r.nav.sigma_rot = a.sigma_rot;
  r.nav.seed = a.seed;
  r.nav.threads = a.threads;
  r.nav.note = [](const std::string& line) { std::cerr << "neopipe compare: " << line << '\n'; };
  r.systems = a.systems;
  r.qrm_images = static_cast<std::size_t>(a.images);
  r.qrm_k = static_cast<std::size_t>(a.k);
  r.bearing_noise_deg = a.bearing_noise;
  r.qualnav_range_error = a.qualnav_range_error;
  r.nx_range_error = a.nx_range_error;
  r.nx_places = static_cast<std::size_t>(std::max<std::int64_t>(a.places, 0));
  return r;
}

void print_table(const CompareArgs& a, const rig::ContenderSet& set, const rig::Comparison& c) {
  std::cout << fmt::format(
      "{} journeys per system on {} ({} objects): the same pairs, arm errors (move {} /mm, rotation {} deg/mm) "
      "and seed {}; {}; panoramic bearing noise {} deg; qualnav range error {}; nx range error {}\n\n",
      c.pairs.size(), a.world, set.world().objects.size(), a.sigma_move, a.sigma_rot, a.seed,
      a.sigma_map ? fmt::format("survey sd {} mm", *a.sigma_map) : std::string("rig survey"), a.bearing_noise,
      a.qualnav_range_error, a.nx_range_error);
  std::cout << fmt::format("{:<12} {:>8} {:>17} {:>10} {:>9} {:>9}  {}\n", "SYSTEM", "GOAL", "95% CI", "PATH/LINE",
                           "FRAMES", "SECONDS", "KNOWS BEFOREHAND");
  for (const rig::ContenderResult& r : c.results) {
    const std::int64_t n = std::max<std::int64_t>(r.summary.run(), 1);
    const rig::Interval ci = rig::wilson_interval(r.summary.reached(), n);
    std::cout << fmt::format("{:<12} {:>7.1f}% {:>8.1f}-{:>5.1f}% {:>10.2f} {:>9.0f} {:>9.1f}  {}\n", r.system,
                             100.0 * static_cast<double>(r.summary.reached()) / static_cast<double>(n), 100 * ci.low,
                             100 * ci.high, r.median_path_ratio, r.mean_frames, r.summary.seconds, r.knows);
  }
  std::cout << "\nPATH/LINE: median arm travel over the straight line between where the tool started and ended, "
               "journeys that reached the goal\n";
  if (!c.tests.empty())
    std::cout << "\nexact McNemar tests (journeys where exactly one of the two reached the goal):\n";
  for (const rig::PairedTest& t : c.tests) {
    std::cout << fmt::format("  {} vs {}: {} only {}, {} only {}, p = {:.3g}\n", c.results[t.a].system,
                             c.results[t.b].system, c.results[t.a].system, t.result.a_only, c.results[t.b].system,
                             t.result.b_only, t.result.p_value);
  }
  std::int64_t unplanned = 0;
  for (const rig::ContenderResult& r : c.results) unplanned += r.unplanned;
  if (unplanned > 0) {
    std::cout << fmt::format(
        "\n{} pairs drawn, {} kept (every system could plan them); could not plan (of the pairs the systems before it "
        "could):",
        c.draws, c.pairs.size());
    for (const rig::ContenderResult& r : c.results) std::cout << fmt::format(" {} {}", r.system, r.unplanned);
    std::cout << '\n';
  }
  std::cout << fmt::format("{:.1f} s of journeys\n", c.seconds);
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Every navigation system on the same world, pairs and arm errors: goal rates with 95% intervals, path "
      "length, frames, prior knowledge, and exact McNemar tests between systems");
  cmd->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  cmd->add_option("--trials", a.trials, "Journeys per system, between the same random pairs")->capture_default_str();
  cmd->add_option(
         "--systems", a.systems,
         fmt::format("Systems to compare, comma-separated (default: all: {})", fmt::join(rig::contender_names(), ",")))
      ->delimiter(',');
  cmd->add_option("--sigma-map", a.sigma_map,
                  "park-kender: survey by moving each object N(0, S) mm per axis instead of through the global camera");
  cmd->add_option("--realism", a.realism, "How real the simulated cameras are: ideal, rig, harsh")
      ->check(CLI::IsMember({"ideal", "rig", "harsh"}))
      ->capture_default_str();
  add_cost_option(cmd, a.cost);
  cmd->add_option("--sigma-move", a.sigma_move, "Arm's translation error, sd mm per mm moved")->capture_default_str();
  cmd->add_option("--sigma-rot", a.sigma_rot, "Arm's heading error, sd degrees per mm moved")->capture_default_str();
  cmd->add_option("--bearing-noise", a.bearing_noise, "Panoramic sensor: sd of each bearing's jitter, degrees")
      ->capture_default_str();
  cmd->add_option("--images", a.images, "qrm: imaging positions of the tour that builds its map")
      ->capture_default_str();
  cmd->add_option("--k", a.k, "qrm: the k nearest landmarks of each image are fused")->capture_default_str();
  cmd->add_option("--qualnav-range-error", a.qualnav_range_error,
                  "qualnav: the range error e of the panoramic sensor's range estimates (0.5: the papers' 50 %)")
      ->capture_default_str();
  cmd->add_option("--nx-range-error", a.nx_range_error, "nx: the range ring's relative error bound (0: off)")
      ->capture_default_str();
  cmd->add_option("--places", a.places, "nx: its exploration stops after this many places")->capture_default_str();
  cmd->add_option("--seed", a.seed, "Seed of the surveys, maps, pair draws and every journey's noise")
      ->capture_default_str();
  cmd->add_option("--threads", a.threads, "Journeys run in parallel on this many threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", a.json, "One JSON object on stdout instead of the table");
  cmd->add_option("--plot", a.plot, "Draw goal rates with their 95% intervals and path ratios (.png)");
  return cmd;
}

int compare_command(const CompareArgs& a) {
  if (a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", a.trials)};
  if (a.images < 1) throw UsageError{fmt::format("--images {}: must be at least 1", a.images)};
  if (a.places < 1) throw UsageError{fmt::format("--places {}: must be at least 1", a.places)};
  if (a.k < 3) throw UsageError{fmt::format("--k {}: a triple needs at least 3 landmarks", a.k)};
  if (!a.plot.empty() && std::filesystem::path(a.plot).extension() != ".png") {
    throw UsageError{fmt::format("--plot {}: the comparison plot is a .png", a.plot)};
  }
  rig::ContendersRequest request = contenders_request(a);
  std::optional<ProgressBar> prep;
  request.progress = [&](const std::string& stage, std::int64_t done, std::int64_t total) {
    if (!prep) prep.emplace(fmt::format("compare: {}", stage), total, true);
    prep->update(done);
    if (done >= total) prep.reset();
  };
  rig::ContenderSet set;
  try {
    set = rig::make_contenders(request);
  } catch (const rig::RequestError& e) {
    throw UsageError{e.what()};
  }
  rig::ComparisonSettings settings;
  settings.trials = a.trials;
  settings.journey.errors = {a.sigma_move, a.sigma_rot};
  settings.journey.realism = sim::parse_realism(a.realism);
  settings.journey.seed = a.seed;
  settings.threads = a.threads;
  const std::int64_t total = a.trials * std::ssize(set.contenders);
  ProgressBar bar("compare", total, true);
  const rig::Comparison c =
      rig::compare_systems(set.contenders, set.world(), settings, [&](std::size_t s, std::int64_t done) {
        bar.update(static_cast<std::int64_t>(s) * a.trials + done, set.contenders[s].system->name());
      });
  bar.clear();
  if (!a.plot.empty()) write_compare_plot(c, a.plot);
  if (a.json) {
    nlohmann::json j = rig::comparison_json(c);
    j["world"] = a.world;
    j["seed"] = a.seed;
    j["sigma_move"] = a.sigma_move;
    j["sigma_rot"] = a.sigma_rot;
    j["sigma_map"] = a.sigma_map ? nlohmann::json(*a.sigma_map) : nlohmann::json(nullptr);
    j["bearing_noise"] = a.bearing_noise;
    j["qualnav_range_error"] = a.qualnav_range_error;
    j["nx_range_error"] = a.nx_range_error;
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  print_table(a, set, c);
  return kExitOk;
}

}  // namespace neopipe::apps
