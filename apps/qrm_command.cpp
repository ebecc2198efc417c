#include "apps/qrm_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "apps/qrm_plot.hpp"
#include "nav/qrm/composition.hpp"
#include "nav/qrm/edc.hpp"
#include "nav/qrm/operators.hpp"
#include "nav/qrm/rng.hpp"
#include "rig/qrm_build.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace qrm = nav::qrm;
using nlohmann::json;

json states_json(qrm::StateSet set) {
  json list = json::array();
  for (const qrm::State s : set) list.push_back(s);
  return list;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Entries where two tables differ, and the first of them.
int differences(const qrm::CompositionEntries& a, const qrm::CompositionEntries& b, std::string* first) {
  int n = 0;
  for (qrm::State s1 = 1; s1 <= qrm::kStateCount; ++s1) {
    for (qrm::State s2 = 1; s2 <= qrm::kStateCount; ++s2) {
      const qrm::StateSet x = a[s1 - 1][s2 - 1];
      const qrm::StateSet y = b[s1 - 1][s2 - 1];
      if (x == y) continue;
      if (n++ == 0) *first = fmt::format("comp({}, {}) = {} against {}", s1, s2, x.to_string(), y.to_string());
    }
  }
  return n;
}

int write_tables(const QrmArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  qrm::CompositionEntries entries{};
  {
    ProgressBar bar("neopipe qrm tables", qrm::kStateCount * qrm::kStateCount, true);
    entries = qrm::generate_composition_entries([&](int done, int) { bar.update(done, "(s1, s2) entries"); });
  }
  const double took = seconds_since(start);
  std::ofstream out(a.write, std::ios::binary | std::ios::trunc);
  out << qrm::format_composition_table(entries);
  out.close();
  if (!out) throw std::runtime_error(a.write + ": cannot write the composition table");
  std::string first;
  const int differ = differences(entries, qrm::composition_table().entries(), &first);
  std::cout << fmt::format("{}: {} feasible triples by branch and bound in {:.1f} s; {}\n", a.write,
                           qrm::CompositionTable(entries).feasible_triples(), took,
                           differ == 0
                               ? std::string("identical to the built-in table")
                               : fmt::format("{} entries differ from the built-in table, first {}", differ, first));
  return kExitOk;
}

int check_table(const QrmArgs& a) {
  const qrm::CompositionEntries entries = qrm::load_composition_table(a.check);
  std::string first;
  const int differ = differences(entries, qrm::composition_table().entries(), &first);
  if (differ != 0) {
    throw std::runtime_error(
        fmt::format("{}: {} entries differ from the built-in table, first {} (built-in)", a.check, differ, first));
  }
  std::cout << fmt::format("{}: identical to the built-in table ({} feasible triples)\n", a.check,
                           qrm::composition_table().feasible_triples());
  return kExitOk;
}

int sample_table(const QrmArgs& a) {
  if (a.sample <= 0) throw UsageError{"--sample N needs N > 0"};
  const auto start = std::chrono::steady_clock::now();
  qrm::SamplingReport r;
  {
    ProgressBar bar("neopipe qrm tables --sample", a.sample, true);
    r = qrm::sample_composition(qrm::composition_table(), a.sample, a.seed,
                                [&](std::int64_t done) { bar.update(done, "configurations"); });
  }
  std::cout << fmt::format(
      "{} random configurations (seed {}), {} degenerate: {} outside the built-in table; {} of its {} feasible "
      "triples met; {:.1f} s\n",
      r.samples, a.seed, r.degenerate, r.outside, r.triples_seen, qrm::composition_table().feasible_triples(),
      seconds_since(start));
  if (r.outside != 0) {
    throw std::runtime_error(fmt::format("the built-in composition table lacks AB:D = {} for AB:C = {}, BC:D = {}",
                                         r.first_outside[2], r.first_outside[0], r.first_outside[1]));
  }
  return kExitOk;
}

int print_tables(const QrmArgs& a) {
  const qrm::CompositionTable& table = qrm::composition_table();
  if (a.json) {
    json j{{"left", json::object()}, {"right", json::object()}, {"inverse", json::object()}};
    json compose = json::array();
    for (qrm::State s = 1; s <= qrm::kStateCount; ++s) {
      const std::string key = std::to_string(s);
      j["left"][key] = states_json(qrm::left_shift(s));
      j["right"][key] = states_json(qrm::right_shift(s));
      j["inverse"][key] = states_json(qrm::StateSet{qrm::inverse(s)});
      json row = json::array();
      for (qrm::State t = 1; t <= qrm::kStateCount; ++t) row.push_back(states_json(table(s, t)));
      compose.push_back(row);
    }
    j["compose"] = compose;
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  std::string text = "Table I: L AB:C -> BC:A, R AB:C -> CA:B, I AB:C -> BA:C\n";
  text += fmt::format("{:>3}  {:<8} {:<8} {:>3}\n", "s", "L", "R", "I");
  for (qrm::State s = 1; s <= qrm::kStateCount; ++s) {
    text += fmt::format("{:>3}  {:<8} {:<8} {:>3}\n", s, qrm::left_shift(s).to_string(),
                        qrm::right_shift(s).to_string(), qrm::inverse(s));
  }
  text += fmt::format("\ncomposition: AB:D given AB:C = s1 and BC:D = s2 ({} feasible triples)\n{:>3} {:>3}  states\n",
                      table.feasible_triples(), "s1", "s2");
  for (qrm::State s1 = 1; s1 <= qrm::kStateCount; ++s1) {
    for (qrm::State s2 = 1; s2 <= qrm::kStateCount; ++s2) {
      text += fmt::format("{:>3} {:>3}  {}\n", s1, s2, table(s1, s2).to_string());
    }
  }
  std::cout << text;
  return kExitOk;
}

int rng_command(const QrmArgs& a) {
  const sim::World world = sim::load_world(a.world);
  if (world.objects.size() < 3) {
    throw std::runtime_error(fmt::format("{}: {} marble{}; the RNG through the EDC needs at least 3", a.world,
                                         world.objects.size(), world.objects.size() == 1 ? "" : "s"));
  }
  std::vector<std::pair<std::size_t, std::size_t>> edges;
  try {
    edges = qrm::true_rng(world.objects);
  } catch (const qrm::DegenerateTripleError& e) {
    throw std::runtime_error(a.world + ": " + e.what());
  }
  if (a.json) {
    json list = json::array();
    for (const auto& [i, j] : edges) list.push_back({i, j});
    std::cout << json{{"edges", list}}.dump() << '\n';
    return kExitOk;
  }
  std::string text = fmt::format("{} marbles, {} RNG edges (i j):\n", world.objects.size(), edges.size());
  for (const auto& [i, j] : edges) text += fmt::format("{} {}\n", i, j);
  std::cout << text;
  return kExitOk;
}

json edges_json(const rig::RngEdges& edges) {
  json list = json::array();
  for (const auto& [i, j] : edges) list.push_back({i, j});
  return list;
}

// A user's world that QRM cannot map: too few marbles, or a degenerate triple (the simulator
// resamples its own worlds; a file is the user's, so it is an error naming both).
sim::World load_qrm_world(const std::string& path) {
  sim::World world = sim::load_world(path);
  if (world.objects.size() < 3) {
    throw std::runtime_error(fmt::format("{}: {} marble{}; a relational map needs at least 3", path,
                                         world.objects.size(), world.objects.size() == 1 ? "" : "s"));
  }
  if (const auto d = qrm::first_degenerate_triple(world.objects)) {
    throw std::runtime_error(path + ": " + qrm::DegenerateTripleError((*d)[0], (*d)[1], (*d)[2]).what());
  }
  return world;
}

void check_build_options(const QrmArgs& a) {
  if (a.images < 1) throw UsageError{"--images N needs N >= 1"};
  if (a.nearest < 3) throw UsageError{"--k K needs K >= 3 (a measurement is a triple)"};
  if (!(a.noise_deg >= 0) || !std::isfinite(a.noise_deg)) throw UsageError{"--noise DEG needs 0 <= DEG"};
}

rig::QrmBuildSettings build_settings(const QrmArgs& a) {
  rig::QrmBuildSettings s;
  s.images = a.images;
  s.nearest = a.nearest;
  s.bearing_noise_deg = a.noise_deg;
  s.seed = a.seed;
  return s;
}

int build_command(const QrmArgs& a) {
  check_build_options(a);
  const sim::World world = load_qrm_world(a.world);
  rig::QrmBuildResult r;
  {
    ProgressBar bar("neopipe qrm build", static_cast<std::int64_t>(a.images), true);
    r = rig::build_qrm_map(world, build_settings(a),
                           [&](std::size_t done) { bar.update(static_cast<std::int64_t>(done), "images"); });
  }
  if (!a.plot.empty()) write_qrm_build_plot(world, r, a.plot);
  const rig::QrmMetrics& last = r.steps.back().metrics;
  double update_us = 0;
  std::size_t triples = 0;
  for (const rig::QrmBuildStep& s : r.steps) {
    update_us += 1e6 * s.image.fuse_seconds;
    triples += s.image.fused.triples;
  }
  const double m5 = triples == 0 ? 0 : update_us / static_cast<double>(triples);
  if (a.json) {
    json per{{"m1", json::array()},           {"m2", json::array()},
             {"m3", json::array()},           {"m4", json::array()},
             {"m5_us", json::array()},        {"landmarks", json::array()},
             {"triples", json::array()},      {"refined", json::array()},
             {"inconsistent", json::array()}, {"rng_precision", json::array()},
             {"rng_recall", json::array()}};
    for (const rig::QrmBuildStep& s : r.steps) {
      per["m1"].push_back(s.metrics.m1);
      per["m2"].push_back(s.metrics.m2);
      per["m3"].push_back(s.metrics.m3);
      per["m4"].push_back(s.metrics.m4);
      per["m5_us"].push_back(s.m5_us);
      per["landmarks"].push_back(s.image.fused.landmarks);
      per["triples"].push_back(s.image.fused.triples);
      per["refined"].push_back(s.image.fused.refined);
      per["inconsistent"].push_back(s.image.fused.inconsistent);
      per["rng_precision"].push_back(s.metrics.versus_truth.precision);
      per["rng_recall"].push_back(s.metrics.versus_truth.recall);
    }
    const json out{{"world", a.world},
                   {"marbles", world.objects.size()},
                   {"images", a.images},
                   {"k", a.nearest},
                   {"seed", a.seed},
                   {"noise_deg", a.noise_deg},
                   {"per_image", per},
                   {"final",
                    {{"m1", last.m1},
                     {"m2", last.m2},
                     {"m3", last.m3},
                     {"m4", last.m4},
                     {"m5_us", m5},
                     {"lost_true_states", last.lost},
                     {"rng_precision", last.versus_truth.precision},
                     {"rng_recall", last.versus_truth.recall},
                     {"rng_equal", last.versus_truth.equal}}},
                   {"inconsistencies", r.inconsistencies},
                   {"rng", edges_json(last.rng)},
                   {"certain_rng", edges_json(last.certain_rng)},
                   {"true_rng", edges_json(r.true_rng)}};
    std::cout << out.dump() << '\n';
    return kExitOk;
  }
  std::string text = fmt::format("{}: {} marbles, {} images, k = {}, seed {}, bearing noise {:g} deg\n", a.world,
                                 world.objects.size(), a.images, a.nearest, a.seed, a.noise_deg);
  text += fmt::format("{:>5} {:>7} {:>7} {:>8} {:>7} {:>8} {:>6}\n", "image", "M1 %", "M2 %", "M3", "M4 %", "M5 us",
                      "incons");
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const rig::QrmBuildStep& s = r.steps[i];
    text += fmt::format("{:>5} {:>7.2f} {:>7.2f} {:>8.4f} {:>7.2f} {:>8.2f} {:>6}\n", i + 1, s.metrics.m1, s.metrics.m2,
                        s.metrics.m3, s.metrics.m4, s.m5_us, s.image.fused.inconsistent);
  }
  text += fmt::format(
      "final: M1 {:.2f} %, M2 {:.2f} %, M3 {:.4f}, M4 {:.2f} %, M5 {:.2f} us per update; {} inconsistencies, {} "
      "relations without their true state\n",
      last.m1, last.m2, last.m3, last.m4, m5, r.inconsistencies, last.lost);
  text += fmt::format("RNG: {} true edges; estimate {} candidates ({} certain), precision {:.3f}, recall {:.3f}{}\n",
                      r.true_rng.size(), last.rng.size(), last.certain_rng.size(), last.versus_truth.precision,
                      last.versus_truth.recall, last.versus_truth.equal ? ", equal to the true RNG" : "");
  std::cout << text;
  return kExitOk;
}

std::vector<std::size_t> size_list(const std::string& text, const std::string& option, std::size_t minimum) {
  std::vector<std::size_t> values;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    std::size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || v < static_cast<long long>(minimum)) {
      throw UsageError{fmt::format("{} {}: expected a comma-separated list of integers >= {}", option, text, minimum)};
    }
    values.push_back(static_cast<std::size_t>(v));
    at = comma + 1;
  }
  return values;
}

int experiment_command(const QrmArgs& a) {
  check_build_options(a);
  if (a.runs < 1) throw UsageError{"--runs N needs N >= 1"};
  if (a.out.empty()) throw UsageError{"--out DIR is required"};
  const std::vector<std::size_t> ks = size_list(a.nearest_list, "--k", 3);
  const std::vector<std::size_t> marbles = size_list(a.marbles_list, "--marbles", 3);
  std::filesystem::create_directories(a.out);
  const std::string path = (std::filesystem::path(a.out) / "qrm_runs.csv").string();
  std::ofstream csv(path, std::ios::trunc);
  if (!csv) throw std::runtime_error(path + ": cannot write");
  csv << "marbles,run,k,image,m1,m2,m3,m4,m5_us,triples,inconsistent,lost,rng_precision,rng_recall,rng_equal\n";
  const auto start = std::chrono::steady_clock::now();
  std::size_t inconsistent = 0;
  std::size_t lost = 0;
  for (const std::size_t n : marbles) {
    rig::QrmExperimentSettings s;
    s.runs = a.runs;
    s.marbles = n;
    s.nearest = ks;
    s.build = build_settings(a);
    std::vector<rig::QrmExperimentRow> rows;
    {
      ProgressBar bar(fmt::format("neopipe qrm experiment ({} marbles)", n), static_cast<std::int64_t>(a.runs), true);
      // Runs end on TBB's threads; the bar is drawn by one at a time.
      std::mutex lock;
      std::int64_t done = 0;
      rows = rig::run_qrm_experiment(s, [&] {
        const std::scoped_lock guard(lock);
        bar.update(++done, "runs");
      });
    }
    std::string text;
    for (const rig::QrmExperimentRow& r : rows) {
      text += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.4g},{},{},{},{:.6g},{:.6g},{}\n", n, r.run,
                          r.nearest, r.image, r.m1, r.m2, r.m3, r.m4, r.m5_us, r.triples, r.inconsistent, r.lost,
                          r.rng_precision, r.rng_recall, r.rng_equal ? 1 : 0);
      inconsistent += r.inconsistent;
      if (r.image == a.images) lost += r.lost;
    }
    csv << text;
  }
  csv.close();
  if (!csv) throw std::runtime_error(path + ": cannot write");
  std::cout << fmt::format(
      "{}: {} runs x {} images for k in {{{}}}, marbles {{{}}}, seed {}, bearing noise {:g} deg; {} inconsistent "
      "measurements, {} final relations without their true state; {:.1f} s\n",
      path, a.runs, a.images, a.nearest_list, a.marbles_list, a.seed, a.noise_deg, inconsistent, lost,
      seconds_since(start));
  return kExitOk;
}

}  // namespace

CLI::App* add_qrm_command(CLI::App& app, QrmArgs& a) {
  CLI::App* cmd =
      app.add_subcommand("qrm", "The qualitative relational map's tools (spec qrm.md): tables, rng, build, experiment");
  cmd->require_subcommand(1);
  CLI::App* tables = cmd->add_subcommand(
      "tables", "Table I (L, R, I) and the composition table; regenerate it by branch and bound or check it");
  tables->add_flag(
      "--json", a.json,
      R"(One JSON object: {"left": {"1": [17], ...}, "right", "inverse", "compose": [[[1,5,11,19], ...]]})");
  CLI::Option* write = tables->add_option(
      "--write", a.write,
      "Recompute the composition table by branch and bound (box [-8,8]^4, depth 40; ~30 s) and write it to FILE");
  CLI::Option* check =
      tables->add_option("--check", a.check, "Read a composition table file and compare it with the built-in table");
  CLI::Option* sample = tables->add_option(
      "--sample", a.sample, "Classify N random configurations and count those outside the built-in table");
  tables->add_option("--seed", a.seed, "Seed of --sample")->capture_default_str();
  write->excludes(check)->excludes(sample);
  check->excludes(sample);
  CLI::App* rng = cmd->add_subcommand("rng",
                                      "The relative neighbourhood graph of a world's true positions, through "
                                      "the EDC state of every triple");
  rng->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  rng->add_flag("--json", a.json, R"(One JSON object: {"edges": [[i, j], ...]}, i < j, sorted)");

  CLI::App* build = cmd->add_subcommand(
      "build",
      "Build a map from panoramas at random imaging positions (random zero direction, no compass) and judge it "
      "against the truth: M1-M5 of spec qrm.md §10 after every image, the estimated RNG against the true one");
  build->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  build->add_option("--images", a.images, "Imaging positions, uniform in the workspace, 10 mm clear of marbles")
      ->capture_default_str();
  build->add_option("--k", a.nearest, "Landmarks used per image: the k nearest by range estimate")
      ->capture_default_str();
  build->add_option("--seed", a.seed, "Seed of the positions, zero directions and noise")->capture_default_str();
  build->add_option("--noise", a.noise_deg, "Bearing noise of the sensor (sd, degrees)")->capture_default_str();
  build->add_flag("--json", a.json,
                  R"(One JSON object: "per_image" {"m1": [...], ..., "m5_us": [...]}, "final", "inconsistencies", )"
                  R"("rng": [[i, j], ...] (not pruned), "certain_rng" (c_ij = 0), "true_rng"; i < j, sorted)");
  build->add_option("--plot", a.plot, "Also draw landmarks, true and estimated RNG and imaging positions to a PNG");

  CLI::App* experiment = cmd->add_subcommand(
      "experiment",
      "Spec qrm.md §10's Monte Carlo: random worlds (marbles uniform in the workspace), random imaging positions, "
      "a map per k; writes DIR/qrm_runs.csv (one row per marbles, run, k, image) for scripts/qrm_plots.py");
  experiment->add_option("--runs", a.runs, "Monte Carlo runs (worlds)")->capture_default_str();
  experiment->add_option("--images", a.images, "Images per run")->capture_default_str();
  experiment->add_option("--k", a.nearest_list, "Comma-separated values of k")->capture_default_str();
  experiment->add_option("--marbles", a.marbles_list, "Comma-separated world sizes")->capture_default_str();
  experiment->add_option("--seed", a.seed, "Seed of the worlds, positions, zero directions and noise")
      ->capture_default_str();
  experiment->add_option("--noise", a.noise_deg, "Bearing noise of the sensor (sd, degrees)")->capture_default_str();
  experiment->add_option("--out", a.out, "Directory for qrm_runs.csv")->required();
  return cmd;
}

int qrm_command(const CLI::App& qrm_app, const QrmArgs& a) {
  if (qrm_app.got_subcommand("rng")) return rng_command(a);
  if (qrm_app.got_subcommand("build")) return build_command(a);
  if (qrm_app.got_subcommand("experiment")) return experiment_command(a);
  if (!a.write.empty()) return write_tables(a);
  if (!a.check.empty()) return check_table(a);
  if (a.sample != 0) return sample_table(a);
  return print_tables(a);
}

}  // namespace neopipe::apps
