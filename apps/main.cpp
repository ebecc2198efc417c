// neopipe: one binary, one subcommand per job.

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "apps/batch_command.hpp"
#include "apps/bench_command.hpp"
#include "apps/calibrate_command.hpp"
#include "apps/compare_command.hpp"
#include "apps/cli_support.hpp"
#include "apps/map_command.hpp"
#include "apps/map_stats_command.hpp"
#include "apps/nav_command.hpp"
#include "apps/nx_command.hpp"
#include "apps/qrm_command.hpp"
#include "apps/qualnav_command.hpp"
#include "apps/run_command.hpp"
#include "apps/sim_command.hpp"
#include "neopipe_version.hpp"

namespace {
using namespace neopipe::apps;

int guarded(const std::string& name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const UsageError& e) {
    print_error(name, e.message + " (see neopipe " + name + " --help)");
    return kExitUsage;
  } catch (const std::exception& e) {
    print_error(name, e.what());
    return kExitFailure;
  }
}

// "sim arm" for `neopipe sim arm ...`: the subcommands given, outermost first.
std::string command_path(const CLI::App& app) {
  std::string path;
  for (const CLI::App* at = &app;;) {
    const auto subs = at->get_subcommands();
    if (subs.empty()) return path;
    at = subs.front();
    path += (path.empty() ? "" : " ") + at->get_name();
  }
}

int run_main(int argc, char** argv) {
  CLI::App app("neopipe: a PIPE-style real-time image pipeline engine", "neopipe");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("neopipe ") + neopipe::version);
  RunArgs run_args;
  BenchArgs bench_args;
  CLI::App* run = add_run_command(app, run_args);
  CLI::App* bench = add_bench_command(app, bench_args);
  CalibrateArgs calibrate_args;
  CLI::App* calibrate = add_calibrate_command(app, calibrate_args);
  SimArgs sim_args;
  CLI::App* sim = add_sim_command(app, sim_args);
  MapArgs map_args;
  CLI::App* map = add_map_command(app, map_args);
  MapStatsArgs map_stats_args;
  CLI::App* map_stats = add_map_stats_command(map, map_stats_args);
  NavArgs nav_args;
  CLI::App* nav = add_nav_command(app, nav_args);
  QrmArgs qrm_args;
  CLI::App* qrm = add_qrm_command(app, qrm_args);
  QualnavArgs qualnav_args;
  CLI::App* qualnav = add_qualnav_command(app, qualnav_args);
  CompareArgs compare_args;
  CLI::App* compare = add_compare_command(app, compare_args);
  BatchArgs batch_args;
  CLI::App* batch = add_batch_command(app, batch_args);
  NxArgs nx_args;
  CLI::App* nx = add_nx_command(app, nx_args);
  // FFmpeg's own log lines would interleave with neopipe's one-line errors; the user can still ask
  // for them by setting the variable.
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);
  if (argc > 1 && argv[1][0] != '-') {
    const auto known = app.get_subcommands([&](const CLI::App* c) { return c->check_name(argv[1]); });
    if (known.empty()) {
      print_error("", std::string("unknown command '") + argv[1] +
                          "' (commands: run, bench, calibrate, sim, map, nav, qrm, qualnav, compare, batch, nx; see neopipe --help)");
      return kExitUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string name = command_path(app);
    print_error(name, std::string(e.what()) + " (see neopipe" + (name.empty() ? "" : " " + name) + " --help)");
    return kExitUsage;
  }
  if (run->parsed()) return guarded("run", [&] { return run_command(run_args); });
  if (bench->parsed()) return guarded("bench", [&] { return bench_command(bench_args); });
  if (calibrate->parsed()) {
    const std::string name = calibrate->got_subcommand("map") ? "calibrate map" : "calibrate";
    return guarded(name, [&] { return calibrate_command(*calibrate, calibrate_args); });
  }
  if (map_stats->parsed()) return guarded("map stats", [&] { return map_stats_command(map_stats_args); });
  if (map->parsed()) return guarded("map", [&] { return map_command(map_args); });
  if (nav->parsed()) return guarded("nav", [&] { return nav_command(nav_args); });
  if (compare->parsed()) return guarded("compare", [&] { return compare_command(compare_args); });
  if (qrm->parsed()) {
    const auto subs = qrm->get_subcommands();
    return guarded("qrm " + subs.front()->get_name(), [&] { return qrm_command(*qrm, qrm_args); });
  }
  if (qualnav->parsed()) {
    const auto subs = qualnav->get_subcommands();
    return guarded("qualnav " + subs.front()->get_name(), [&] { return qualnav_command(*qualnav, qualnav_args); });
  }
  if (batch->parsed()) {
    const auto subs = batch->get_subcommands();
    return guarded("batch " + subs.front()->get_name(), [&] { return batch_command(*batch, batch_args); });
  }
  if (nx->parsed()) {
    const auto subs = nx->get_subcommands();
    return guarded("nx " + subs.front()->get_name(), [&] { return nx_command(*nx, nx_args); });
  }
  if (sim->parsed()) {
    const auto subs = sim->get_subcommands();
    return guarded("sim " + subs.front()->get_name(), [&] { return sim_command(*sim, sim_args); });
  }
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_main(argc, argv);
  } catch (const std::exception& e) {  // only a bug gets here: every command reports its own errors
    print_error("", e.what());
    return kExitFailure;
  }
}
