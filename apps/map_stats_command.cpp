#include "apps/map_stats_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/map_stats_plot.hpp"
#include "apps/progress.hpp"
#include "batch/stats_shards.hpp"
#include "nav/mapmaker/statistics.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;

// The whole of `text` as a finite number, or nothing.
std::optional<double> number(const std::string& text) {
  std::istringstream in(text);
  double v = 0;
  if (!(in >> v) || !(in >> std::ws).eof() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::vector<std::size_t> populations_of(const std::string& text) {
  std::vector<std::size_t> out;
  for (const double v : parse_range(text, "--population", 20)) {
    if (v < 0 || v != std::floor(v) || v > 1e7) {
      throw UsageError{fmt::format("--population {}: populations are whole numbers >= 0", text)};
    }
    out.push_back(static_cast<std::size_t>(v));
  }
  return out;
}

void write_csv(std::ostream& out, const std::vector<mm::StatisticsRow>& rows) {
  out << "window,margin,population,trials,density";
  for (const std::string_view name : mm::count_names()) {
    out << fmt::format(",{0}_mean,{0}_sd,{0}_ci_low,{0}_ci_high", name);
  }
  out << ",poisson_p_new,poisson_new_parkways,poisson_new_parkways_bounded\n";
  for (const mm::StatisticsRow& r : rows) {
    out << fmt::format("{},{},{},{},{}", r.window.side, r.window.margin, r.population, r.trials, r.density);
    for (const mm::Summary& s : r.counts) out << fmt::format(",{},{},{},{}", s.mean, s.sd, s.ci_low, s.ci_high);
    out << fmt::format(",{},{},{}\n", r.poisson_probability, r.poisson_new_parkways, r.poisson_new_parkways_bounded);
  }
}

}  // namespace

std::vector<double> parse_range(const std::string& text, const std::string& option, double default_step) {
  const auto bad = [&] {
    return UsageError{fmt::format("{} {}: expected A..B, A..B:STEP or a list A,B,C of numbers", option, text)};
  };
  std::vector<double> values;
  const auto dots = text.find("..");
  if (dots == std::string::npos) {
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
      const auto v = number(item);
      if (!v) throw bad();
      values.push_back(*v);
    }
    if (values.empty() || text.back() == ',') throw bad();
    return values;
  }
  const auto colon = text.find(':', dots);
  const auto from = number(text.substr(0, dots));
  const auto to = number(text.substr(dots + 2, colon == std::string::npos ? std::string::npos : colon - dots - 2));
  const auto step = colon == std::string::npos ? std::optional<double>(default_step) : number(text.substr(colon + 1));
  if (!from || !to || !step) throw bad();
  if (!(*step > 0)) throw UsageError{fmt::format("{} {}: the step must be > 0", option, text)};
  if (*to < *from) throw UsageError{fmt::format("{} {}: the range is empty (B < A)", option, text)};
  // Values from + k step: multiplying (not accumulating) keeps 0.1-steps from drifting past B.
  for (std::size_t k = 0;; ++k) {
    const double v = *from + static_cast<double>(k) * *step;
    if (v > *to + 1e-9 * std::max(1.0, std::abs(*to))) break;
    values.push_back(v);
    if (values.size() > 100000) throw UsageError{fmt::format("{} {}: more than 100000 values", option, text)};
  }
  return values;
}

CLI::App* add_map_stats_command(CLI::App* map, MapStatsArgs& a) {
  CLI::App* cmd = map->add_subcommand(
      "stats",
      "Parkway statistics over random worlds (paper Fig. 7 and 11): parkways of each kind and strongly connected "
      "components with and without trajectories against population, 95% CIs, vs the Poisson estimate");
  cmd->footer(
      "One CSV row per (window, population); every count has _mean, _sd, _ci_low, _ci_high (Student t, 95%).\n"
      "Worlds: uniform objects in a size x size square, one stream per (seed, trial), nested in population\n"
      "and shared by every window; results are identical for any --threads. See docs/parkway-statistics.md.\n"
      "Example: neopipe map stats --size 100 --window 2..10 --population 0..400 --trials 20 --plot fig7.png");
  cmd->add_option("--size", a.size, "World side r, mm (the world is r x r)")->capture_default_str();
  cmd->add_option("--window", a.window, "Window sides a: A..B[:STEP] (step 1) or a list A,B,C")->capture_default_str();
  cmd->add_option("--population", a.population, "Populations: A..B[:STEP] (step 20) or a list A,B,C")
      ->capture_default_str();
  cmd->add_option("--margin-factor", a.margin_factor, "Corner margin m as a fraction of a")->capture_default_str();
  cmd->add_option("--trials", a.trials, "Random worlds per (window, population)")->capture_default_str();
  cmd->add_option("--seed", a.seed, "Random seed")->capture_default_str();
  cmd->add_option("--threads", a.threads, "Worker threads (0: all)")->capture_default_str();
  cmd->add_option("--csv", a.csv, "Write the CSV here (default stdout)");
  cmd->add_option("--plot", a.plot, "Draw Fig. 7 and Fig. 11 into this PNG");
  cmd->add_flag("-q,--quiet", a.quiet, "No progress bar");
  cmd->add_option("--shard", a.shard,
                  "Compute only shard I of K of the (window, population) rows, under a \"# neopipe shard\" line; "
                  "`neopipe batch merge-shards` merges the K shards into the unsharded CSV")
      ->type_name("I/K");
  // `neopipe map` needs --world or --blobs, but `map stats` makes its own worlds; main.cpp dispatches
  // to stats before map's checks run.
  map->require_subcommand(0, 1);
  return cmd;
}

int map_stats_command(const MapStatsArgs& a) {
  if (!(a.size > 0) || !std::isfinite(a.size)) throw UsageError{fmt::format("--size {}: must be > 0 mm", a.size)};
  mm::StatisticsOptions o;
  o.size = a.size;
  o.windows = parse_range(a.window, "--window", 1);
  for (const double w : o.windows) {
    if (!(w > 0) || !(w < a.size)) {
      throw UsageError{fmt::format("--window {}: every side must be > 0 and smaller than --size {}", a.window, a.size)};
    }
  }
  o.populations = populations_of(a.population);
  if (a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", a.trials)};
  o.trials = static_cast<std::size_t>(a.trials);
  if (a.threads < 0) throw UsageError{fmt::format("--threads {}: must be >= 0", a.threads)};
  o.threads = a.threads;
  if (!(a.margin_factor > 0 && a.margin_factor < 0.5)) {
    throw UsageError{fmt::format("--margin-factor {}: must lie strictly between 0 and 0.5", a.margin_factor)};
  }
  o.margin_factor = a.margin_factor;
  o.seed = a.seed;
  if (!a.plot.empty() && std::filesystem::path(a.plot).extension() != ".png") {
    throw UsageError{fmt::format("--plot {}: the plot must be a .png file", a.plot)};
  }
  // Open the outputs before hours of simulation, so that a bad path fails at once.
  std::ofstream csv_file;
  if (!a.csv.empty()) {
    csv_file.open(a.csv);
    if (!csv_file) throw std::runtime_error(fmt::format("--csv {}: cannot write this file", a.csv));
  }
  if (!a.plot.empty() && !std::ofstream(a.plot, std::ios::app)) {
    throw std::runtime_error(fmt::format("--plot {}: cannot write this file", a.plot));
  }

  std::optional<batch::ShardSpec> shard;
  if (!a.shard.empty()) {
    if (!a.plot.empty()) throw UsageError{"--plot draws every row: draw it from the merged shards, not with --shard"};
    try {
      shard = batch::parse_shard(a.shard);
    } catch (const std::invalid_argument& e) {
      throw UsageError{e.what()};
    }
  }
  const auto all_rows = static_cast<std::int64_t>(o.windows.size() * o.populations.size());
  const batch::ItemRange range = shard ? batch::shard_range(all_rows, *shard) : batch::ItemRange{0, all_rows};

  std::vector<mm::StatisticsRow> rows;
  {
    ProgressBar bar("neopipe map stats", range.size() * static_cast<std::int64_t>(o.trials), !a.quiet);
    std::size_t before = 0;
    // A shard's rows are runs of one window and consecutive populations; every row depends on its own
    // (window, population, trials, seed) only, so it is the same computed alone as among all rows.
    for (const batch::GridRun& run : batch::grid_runs(o.windows.size(), o.populations.size(), range)) {
      mm::StatisticsOptions part = o;
      part.windows = {o.windows[run.outer]};
      part.populations.assign(o.populations.begin() + static_cast<std::ptrdiff_t>(run.inner_first),
                              o.populations.begin() + static_cast<std::ptrdiff_t>(run.inner_last));
      const auto got = mm::parkway_statistics(part, [&](std::size_t done, std::size_t) {
        bar.update(static_cast<std::int64_t>(before + done), "worlds");
      });
      rows.insert(rows.end(), got.begin(), got.end());
      before += (run.inner_last - run.inner_first) * o.trials;
    }
  }
  std::ostream& out = a.csv.empty() ? std::cout : csv_file;
  if (shard) out << batch::shard_table_line(*shard, range, all_rows);
  write_csv(out, rows);
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("--csv {}: writing failed", a.csv.empty() ? "stdout" : a.csv));
  if (!a.plot.empty()) write_map_stats_plot(rows, a.plot);
  return kExitOk;
}

}  // namespace neopipe::apps
