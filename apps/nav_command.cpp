#include "apps/nav_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/cli_support.hpp"
#include "apps/map_plot.hpp"
#include "apps/nav_video.hpp"
#include "apps/outcome_table.hpp"
#include "apps/progress.hpp"
#include "apps/reliability_diagram.hpp"
#include "batch/shard.hpp"
#include "nav/mapmaker/map_maker.hpp"
#include "rig/experiment.hpp"
#include "rig/journey.hpp"
#include "rig/park_kender.hpp"
#include "rig/reports.hpp"
#include "rig/seeds.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;
namespace nv = nav::navigator;
using nlohmann::json;

using Setup = rig::NavSetup;

rig::NavRequest nav_request(const NavArgs& a) {
  rig::NavRequest r;
  r.world = a.world;
  r.cost = a.cost;
  r.sigma_map = a.sigma_map;
  r.realism = a.realism;
  r.cache_dir = a.cache_dir;
  r.no_cache = a.no_cache;
  r.sigma_move = a.sigma_move;
  r.sigma_rot = a.sigma_rot;
  r.seed = a.seed;
  r.no_recovery = a.no_recovery;
  r.no_slide_goals = a.no_slide_goals;
  r.navigator = a.navigator;
  r.descriptions = a.descriptions;
  r.min_reliability = a.min_reliability;
  r.window = a.window;
  r.threads = a.threads;
  r.note = [](const std::string& line) { std::cerr << "neopipe nav: " << line << '\n'; };
  return r;
}

Setup make_setup(const NavArgs& a) {
  try {
    return rig::nav_setup(nav_request(a));
  } catch (const rig::RequestError& e) {
    throw UsageError{e.what()};
  }
}

// The surveyed position of every object beside its true one: what the map-maker believed, for
// replaying its choices (`neopipe map`) or finding the survey error behind a failed step.
void write_survey_csv(const std::string& path, const Setup& s) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("--survey-csv {}: cannot open for writing", path));
  out << "id,x,y,true_x,true_y,error\n";
  const auto& surveyed = s.survey.workspace.objects;
  for (std::size_t i = 0; i < surveyed.size(); ++i) {
    const Eigen::Vector2d& t = s.world.objects[i];
    out << fmt::format("{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", i, surveyed[i].x(), surveyed[i].y(), t.x(), t.y(),
                       (surveyed[i] - t).norm());
  }
  if (!out.flush()) throw std::runtime_error(fmt::format("--survey-csv {}: write failed", path));
}

std::string survey_line(const rig::Survey& s) {
  return fmt::format(
      "survey: {}, position sd {:.4f} mm as the map-maker is told; against the truth RMS {:.4f} mm, max {:.4f} mm",
      s.method == "global_camera" ? fmt::format("global camera ({} realism) + calibration", s.realism)
                                  : std::string("Gaussian error"),
      s.sigma, s.rms_error, s.max_error);
}

json held_json(const rig::JourneyResult& r, std::size_t entry) {
  for (auto it = r.held.rbegin(); it != r.held.rend(); ++it) {
    if (it->entry == entry) {
      return {{"intended", it->intended}, {"held", it->actual}, {"offset", it->offset}, {"correct", it->correct}};
    }
  }
  return nullptr;
}

int one_journey(const NavArgs& a, const Setup& s) {
  const auto check_id = [](const char* option, std::int64_t id) {
    if (id < 0) throw UsageError{fmt::format("{} {}: object ids start at 0", option, id)};
    return static_cast<std::uint32_t>(id);
  };
  const std::uint32_t from = check_id("--from", *a.from);
  const std::uint32_t to = check_id("--to", *a.to);
  std::optional<NavVideo> video;
  if (!a.video.empty()) video.emplace(a.video, s.settings.map.window.side, s.settings.navigator.camera.side_px);
  const auto system =
      rig::make_park_kender(s.survey, s.settings, *mm::parse_criterion(a.cost), video ? &*video : nullptr);
  std::unique_ptr<rig::Plan> plan;
  try {
    plan = system->plan(from, to);
  } catch (const rig::UnreachableGoal& e) {
    print_error("nav", e.what());
    return kExitUnreachable;
  }
  if (!plan->refused.empty()) {
    print_error("nav", fmt::format("refused: {} (--min-reliability)", plan->refused));
    return kExitUnreachable;
  }
  const mm::Route& route = rig::route_of(*plan);
  rig::JourneySettings journey = s.settings.journey;
  if (a.as_trial) {
    if (*a.as_trial < 0) throw UsageError{fmt::format("--as-trial {}: trials are numbered from 0", *a.as_trial)};
    journey.seed = rig::trial_seed(journey.seed, *a.as_trial);
  }
  const rig::JourneyResult r = rig::run_journey(*system, *plan, s.world, journey);
  if (video) video->close();
  const nv::JourneyReport& report = *rig::navigator_report(r.travel);

  const auto& entries = route.custom_map.entries;
  if (a.json) {
    json j = {{"from", route.start},
              {"to", route.goal},
              {"cost", mm::criterion_name(route.criterion)},
              {"custom_map", nav::format_custom_map(route.custom_map)},
              {"planned",
               {{"D", route.distance},
                {"U", route.unreliability},
                {"forecast", route.forecast},
                {"landmark_distance", route.landmark_distance},
                {"steps", route.steps.size()}}},
              {"outcome", rig::outcome_name(r.outcome)},
              {"reached_goal", rig::reached_goal(r.outcome)},
              {"ending", rig::ending_name(r.travel.ending)},
              {"reason", r.travel.reason},
              {"recoveries", r.travel.recoveries},
              {"frames", r.frames},
              {"commanded_travel", r.arm.commanded_travel},
              {"arm_travel", r.arm.true_travel},
              {"refused_moves", r.arm.refused_moves},
              {"survey", rig::survey_json(s.survey)},
              {"seed", a.seed}};
    json list = json::array();
    for (std::size_t e = 0; e < entries.size(); ++e) {
      json item = {{"entry", e}, {"map", nav::format_entry(entries[e])}, {"truth", held_json(r, e)}};
      for (const nv::EntryRecord& rec : report.entries) {
        if (rec.entry != e) continue;
        item["verified"] = rec.verified;
        item["measured_qoc"] = rec.measured_qoc ? json(*rec.measured_qoc) : json(nullptr);
        item["recoveries"] = rec.recoveries;
        item["frames"] = rec.frames;
      }
      list.push_back(item);
    }
    j["entries"] = list;
    std::cout << j.dump() << '\n';
  } else {
    std::cout << survey_line(s.survey) << '\n'
              << fmt::format("route {} -> {} by {}:\n", route.start, route.goal, mm::criterion_name(route.criterion))
              << mm::route_table(route) << "custom map:\n"
              << nav::format_custom_map(route.custom_map) << "\n\n"
              << fmt::format("{:>5}  {:<40} {:>8} {:>6} {:>7} {:>8} {:>4} {:>5} {:>6}\n", "ENTRY", "MAP", "INTENDED",
                             "HELD", "OFF mm", "VERIFIED", "QOC", "RECOV", "FRAMES");
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const json h = held_json(r, e);
      std::string verified = "-";
      std::string qoc = "-";
      std::string recov = "-";
      std::string frames = "-";
      for (const nv::EntryRecord& rec : report.entries) {
        if (rec.entry != e) continue;
        verified = rec.verified ? "yes" : "no";
        qoc = rec.measured_qoc ? std::to_string(*rec.measured_qoc) : "-";
        recov = std::to_string(rec.recoveries);
        frames = std::to_string(rec.frames);
      }
      std::cout << fmt::format("{:>5}  {:<40} {:>8} {:>6} {:>7} {:>8} {:>4} {:>5} {:>6}{}\n", e,
                               nav::format_entry(entries[e]),
                               h.is_null() ? "-" : std::to_string(h["intended"].get<std::uint32_t>()),
                               h.is_null() ? "-" : std::to_string(h["held"].get<std::uint32_t>()),
                               h.is_null() ? "-" : fmt::format("{:.2f}", h["offset"].get<double>()), verified, qoc,
                               recov, frames, !h.is_null() && !h["correct"].get<bool>() ? "  WRONG" : "");
    }
    std::cout << fmt::format("\noutcome: {} (navigator: {}{}{}); {} recoveries\n", rig::outcome_name(r.outcome),
                             rig::ending_name(r.travel.ending), r.travel.reason.empty() ? "" : ", ", r.travel.reason,
                             r.travel.recoveries)
              << fmt::format(
                     "frames {}, commanded travel {:.1f} mm, arm travel {:.1f} mm{}\n", r.frames,
                     r.arm.commanded_travel, r.arm.true_travel,
                     r.arm.refused_moves > 0 ? fmt::format(", {} moves out of reach", r.arm.refused_moves) : "");
  }
  if (!a.plot.empty()) {
    ExecutedRoute executed;
    executed.track = r.arm.track;
    const double half = s.settings.map.window.side / 2;
    for (const rig::HeldLandmark& h : r.held) executed.held_windows.emplace_back(h.tool - Eigen::Vector2d(half, half));
    executed.caption = std::string(rig::outcome_name(r.outcome));
    write_map_plot(system->maker(), route, a.plot, &executed);
  }
  return kExitOk;
}

// --shard I/K: journeys I of K, as JSON for `neopipe batch merge-shards` (rig/trials_shards.hpp).
std::optional<rig::TrialShard> trial_shard(const NavArgs& a) {
  if (a.shard.empty()) return std::nullopt;
  batch::ShardSpec spec;
  try {
    spec = batch::parse_shard(a.shard);
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  const batch::ItemRange r = batch::shard_range(*a.trials, spec);
  return rig::TrialShard{spec.index, spec.count, *a.trials, r.first, r.last};
}

int trials(const NavArgs& a, const Setup& s) {
  const std::optional<rig::TrialShard> shard = trial_shard(a);
  ProgressBar bar("nav", shard ? shard->last - shard->first : *a.trials, true);
  rig::TrialsReport report;
  try {
    report = rig::trials_report(
        nav_request(a), s, *a.trials, [&](std::int64_t done) { bar.update(done); }, shard);
  } catch (const rig::RequestError& e) {
    throw UsageError{e.what()};
  }
  bar.clear();
  const rig::TrialsSummary& t = report.summary;
  const json& j = report.json;
  if (shard) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  if (!a.diagram.empty()) {
    std::vector<ForecastOutcome> forecasts;
    for (const rig::TrialRecord& r : t.trials)
      if (!r.refused) forecasts.push_back({r.planned_reliability, rig::reached_goal(r.outcome)});
    write_reliability_diagram(
        forecasts,
        fmt::format("{}: {} journeys, {}, seed {}", std::filesystem::path(a.world).filename().string(), t.run(),
                    a.sigma_map ? fmt::format("survey sd {} mm", *a.sigma_map) : std::string("rig survey"), a.seed),
        a.diagram);
  }
  if (a.json) {
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  const std::int64_t asked = std::ssize(t.trials);
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  std::cout << fmt::format(
      "{} journeys on {} ({} objects), cost {}, move {} /mm, rotation {} deg/mm, recovery {}, seed {}\n{}\n\n"
      "{:<20} {:>7} {:>8}  {}\n",
      n, a.world, s.world.objects.size(), a.cost, a.sigma_move, a.sigma_rot, a.no_recovery ? "off" : "on", a.seed,
      survey_line(s.survey), "OUTCOME", "COUNT", "RATE", "95% CI");
  print_outcome_rows(std::cout, t, n);
  if (a.min_reliability > 0) {
    std::cout << fmt::format("{:<20} {:>7}   of {} asked: routes forecast below R {} were not attempted\n", "refused",
                             t.refused, asked, a.min_reliability);
  }
  std::cout << fmt::format(
      "\nplanned: mean D {:.1f} mm; the map-maker forecast {:.2f}% of the journeys to reach the goal (mean R)\n"
      "recoveries: {} by the map's QOC rules, {} returns to an earlier landmark for another choice\n"
      "frames {} in {:.2f} s: {:.0f} frames/s; mean arm travel {:.1f} mm (commanded {:.1f} mm)\n",
      j["mean_planned_distance"].get<double>(), 100 * j["mean_planned_reliability"].get<double>(),
      j["recoveries"]["qoc_rules"].get<std::int64_t>(), j["recoveries"]["backtracks"].get<std::int64_t>(), t.frames,
      t.seconds, j["frames_per_second"].get<double>(), j["mean_arm_travel"].get<double>(),
      j["mean_commanded_travel"].get<double>());
  return kExitOk;
}

}  // namespace

CLI::App* add_nav_command(CLI::App& app, NavArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "nav", "Navigator in the simulator: one journey (--from/--to) or --trials N random journeys and their outcomes");
  cmd->add_option(
         "--system", a.system,
         "park-kender: the map-maker's custom map on the onboard camera; qrm: the qualitative relational map "
         "(qrm.md §8) on the panoramic sensor, its map built by an imaging tour first; qualnav: viewframes and a "
         "visual memory recorded along each journey's taught route (qualnav.md §7) on the panoramic sensor; nx: "
         "NX (qualnav.md §9) on the range ring, its map learned by exploring first")
      ->check(CLI::IsMember({"park-kender", "qrm", "qualnav", "nx"}))
      ->capture_default_str();
  cmd->add_option("--world", a.world, "World file (YAML, as neopipe sim world writes)")->required();
  cmd->add_option("--from", a.from, "Start object id (one journey)");
  cmd->add_option("--to", a.to, "Goal object id (one journey)");
  cmd->add_option("--as-trial", a.as_trial,
                  "One journey: the arm's and camera's noise of journey I of --trials with the same --seed (to replay "
                  "a trial exactly: its from/to are in the trials JSON, numbered from 0)");
  add_cost_option(cmd, a.cost);
  cmd->add_option("--sigma-map", a.sigma_map,
                  "Survey by moving each object N(0, S) mm per axis instead of through the global camera and its "
                  "calibration (the default)");
  cmd->add_option("--realism", a.realism,
                  "How real the simulated cameras are: ideal (flat disks, OpenCV's lens: what the models assume), rig "
                  "(spheres under a lamp, a lens and sensor the models do not fit exactly), harsh")
      ->check(CLI::IsMember({"ideal", "rig", "harsh"}))
      ->capture_default_str();
  cmd->add_option("--calibration-cache", a.cache_dir,
                  "Folder of cached global camera calibrations (default: $NEOPIPE_CACHE_DIR, $XDG_CACHE_HOME/neopipe "
                  "or ~/.cache/neopipe)")
      ->type_name("DIR");
  cmd->add_flag("--no-calibration-cache", a.no_cache, "Calibrate the global camera afresh, and cache nothing");
  cmd->add_option("--sigma-move", a.sigma_move, "Arm's translation error, sd mm per mm moved")->capture_default_str();
  cmd->add_option("--sigma-rot", a.sigma_rot, "Arm's heading error, sd degrees per mm moved")->capture_default_str();
  cmd->add_option(
         "--seed", a.seed,
         "Seed of the survey (its images' noise or Gaussian errors), the start/goal draws, arm errors, camera noise")
      ->capture_default_str();
  cmd->add_option("--trials", a.trials, "Run N journeys between random reachable pairs and print the outcome table");
  cmd->add_flag("--no-recovery", a.no_recovery,
                "Navigator ignores the map's recovery rules and never goes back to try another candidate");
  cmd->add_flag("--no-slide-goals", a.no_slide_goals,
                "The map does not say where each slide's goal enters (\"Trajp:97@85/-3~8/12\"), as the paper's maps: "
                "the navigator takes the first newcomer");
  cmd->add_option("--min-reliability", a.min_reliability,
                  "Refuse routes whose forecast reliability is below P, after trying the most reliable route (exit 3; "
                  "--trials counts refusals apart from failures)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--navigator", a.navigator,
                  "tracking: the window's heading is dead-reckoned from marbles tracked across moves (an extension); "
                  "paper: no compass and no such memory, as the paper's navigator")
      ->check(CLI::IsMember({"tracking", "paper"}))
      ->capture_default_str();
  cmd->add_option("--descriptions", a.descriptions,
                  "paper: the map describes landmarks as the paper does (Obvious, Isol); extended: also Far and "
                  "Near, the objects in view farthest from and nearest to the reference")
      ->check(CLI::IsMember({"paper", "extended"}))
      ->capture_default_str();
  cmd->add_option("--window", a.window, "View window side a, mm")->capture_default_str();
  cmd->add_option("--threads", a.threads, "Journeys run in parallel on this many threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", a.json, "One JSON object on stdout instead of text");
  cmd->add_option("--plot", a.plot, "One journey: draw the world, planned and executed routes (.png or .svg)");
  cmd->add_option("--reliability-diagram", a.diagram,
                  "Trials: draw the forecast against the outcome (bins of planned R, 95% CIs) to this PNG");
  cmd->add_option("--survey-csv", a.survey_csv,
                  "Write every object's surveyed position (what the map-maker believes) beside the true one: CSV "
                  "id,x,y,true_x,true_y,error");
  cmd->add_option("--images", a.images, "qrm: imaging positions of the tour that builds the robot's map")
      ->capture_default_str();
  cmd->add_option("--k", a.k, "qrm: the k nearest landmarks of each image are fused into the map")
      ->capture_default_str();
  cmd->add_option("--pairs", a.pairs,
                  "qrm: journeys between the pairs of a trials JSON (its journeys' from/to, e.g. Park & Kender's "
                  "--trials --json) instead of --trials random draws, so the two systems meet the same pairs")
      ->type_name("FILE");
  cmd->add_option("--shard", a.shard,
                  "Trials: run only shard I of K of the --trials journeys (seeded as in the whole run) and print "
                  "them as JSON; `neopipe batch merge-shards` merges the K shards into the unsharded --json")
      ->type_name("I/K");
  cmd->add_option("--range-error", a.range_error,
                  "qualnav: the range error e the sensor's range estimates carry (a factor log-uniform in [1/(1+e), "
                  "1+e] per sighting) and the navigator's intervals allow (default 0.5, the papers' 50 %); nx: the "
                  "range ring's relative error bound (default 0.1; 0: off)");
  cmd->add_option("--places", a.places, "nx: the exploration stops after this many places")->capture_default_str();
  cmd->add_option("--taught-route", a.taught_route,
                  "qualnav: the routes the harness teaches (its memory): shortest (clear of the marbles) or detour "
                  "(via a point off to the side, leaving shortcuts to find)")
      ->check(CLI::IsMember({"shortest", "detour"}))
      ->capture_default_str();
  cmd->add_option("--level", a.level,
                  "qualnav: the level a journey starts at: viewframes (viewframe headings all the way) or regions "
                  "(orientation regions of the memory crossed by the productions' headings, the viewframe level "
                  "finishing; qualnav.md §7)")
      ->check(CLI::IsMember({"viewframes", "regions"}))
      ->capture_default_str();
  cmd->add_option("--video", a.video, "One journey: the onboard view with the blobs marked (.mp4, .avi, .mkv)");
  return cmd;
}

int nav_command(const NavArgs& a) {
  if (!a.shard.empty() && a.system != "park-kender") throw UsageError{"--shard: only --system park-kender's trials"};
  if (a.range_error && a.system != "qualnav" && a.system != "nx") {
    throw UsageError{"--range-error goes with --system qualnav or nx"};
  }
  if (a.taught_route != NavArgs{}.taught_route && a.system != "qualnav") {
    throw UsageError{"--taught-route goes with --system qualnav"};
  }
  if (a.level != NavArgs{}.level && a.system != "qualnav") throw UsageError{"--level goes with --system qualnav"};
  if (a.system == "qrm") return qrm_nav_command(a);
  if (a.system == "qualnav") return qualnav_nav_command(a);
  if (a.system == "nx") return nx_nav_command(a);
  if (!a.pairs.empty()) throw UsageError{"--pairs goes with --system qrm"};
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (a.from.has_value() == a.trials.has_value()) {
    throw UsageError{"give either --from I --to J (one journey) or --trials N (random journeys)"};
  }
  if (a.trials && *a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", *a.trials)};
  if (a.trials && a.as_trial) throw UsageError{"--as-trial replays one journey: give --from/--to, not --trials"};
  if (!a.trials && !a.diagram.empty()) throw UsageError{"--reliability-diagram goes with --trials"};
  if (!a.shard.empty() && (!a.trials || !a.json || !a.diagram.empty())) {
    throw UsageError{"--shard goes with --trials N --json (and without --reliability-diagram: draw it from the merge)"};
  }
  if (a.trials) (void)trial_shard(a);  // a bad --shard fails before the survey, not after
  if (a.trials && (!a.plot.empty() || !a.video.empty())) {
    throw UsageError{"--plot and --video draw one journey: use them with --from/--to, not --trials"};
  }
  const Setup s = make_setup(a);
  if (!a.survey_csv.empty()) write_survey_csv(a.survey_csv, s);
  return a.trials ? trials(a, s) : one_journey(a, s);
}

}  // namespace neopipe::apps
