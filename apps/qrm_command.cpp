#include "apps/qrm_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "nav/qrm/composition.hpp"
#include "nav/qrm/operators.hpp"
#include "nav/qrm/rng.hpp"
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

}  // namespace

CLI::App* add_qrm_command(CLI::App& app, QrmArgs& a) {
  CLI::App* cmd = app.add_subcommand("qrm", "The qualitative relational map's tools (spec qrm.md): tables, rng");
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
  return cmd;
}

int qrm_command(const CLI::App& qrm_app, const QrmArgs& a) {
  if (qrm_app.got_subcommand("rng")) return rng_command(a);
  if (!a.write.empty()) return write_tables(a);
  if (!a.check.empty()) return check_table(a);
  if (a.sample != 0) return sample_table(a);
  return print_tables(a);
}

}  // namespace neopipe::apps
