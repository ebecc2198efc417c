#include "apps/nav_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "apps/cli_support.hpp"
#include "apps/map_plot.hpp"
#include "apps/nav_video.hpp"
#include "apps/progress.hpp"
#include "apps/reliability_diagram.hpp"
#include "nav/mapmaker/map_maker.hpp"
#include "rig/calibration_cache.hpp"
#include "rig/experiment.hpp"
#include "rig/journey.hpp"
#include "rig/park_kender.hpp"
#include "rig/seeds.hpp"
#include "rig/survey.hpp"
#include "rig/trials.hpp"
#include "sim/realism.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;
namespace nv = nav::navigator;
using nlohmann::json;

void check_non_negative(const char* option, double value, const char* unit) {
  if (!(value >= 0) || !std::isfinite(value))
    throw UsageError{fmt::format("{} {}: must be >= 0 {}", option, value, unit)};
}

struct Setup {
  sim::World world;
  rig::Survey survey;
  rig::ExperimentSettings settings;
};

Setup make_setup(const NavArgs& a) {
  if (!(a.window > 0) || !std::isfinite(a.window))
    throw UsageError{fmt::format("--window {}: must be > 0 mm", a.window)};
  if (a.sigma_map) check_non_negative("--sigma-map", *a.sigma_map, "mm");
  check_non_negative("--sigma-move", a.sigma_move, "mm per mm");
  check_non_negative("--sigma-rot", a.sigma_rot, "degrees per mm");
  Setup s;
  s.world = sim::load_world(a.world);  // WorldError: one line naming the file
  if (s.world.objects.size() < 2) {
    throw mm::MapError(
        fmt::format("{}: the world has {} objects; a journey needs at least two", a.world, s.world.objects.size()));
  }
  if (a.window > std::min(s.world.size.x(), s.world.size.y())) {
    throw mm::MapError(
        fmt::format("--window {} mm is larger than the {}x{} mm world", a.window, s.world.size.x(), s.world.size.y()));
  }
  const sim::Realism realism = sim::parse_realism(a.realism);  // checked by the option already
  if (a.sigma_map) {
    s.survey = rig::gaussian_survey(s.world, *a.sigma_map, a.seed);
  } else {
    rig::SurveySettings survey;
    survey.camera.realism = realism;
    survey.camera.seed = a.seed;
    if (!a.no_cache) {
      survey.cache_dir = a.cache_dir.empty() ? rig::CalibrationCache::default_dir()
                                             : std::optional<std::filesystem::path>(a.cache_dir);
    }
    survey.note = [](const std::string& line) { std::cerr << "neopipe nav: " << line << '\n'; };
    s.survey = rig::global_camera_survey(s.world, survey);
  }
  rig::ExperimentConfig config;
  config.window = a.window;
  config.arm = {a.sigma_move, a.sigma_rot};
  config.recovery = !a.no_recovery;
  config.track_heading = a.navigator == "tracking";
  config.extended_descriptions = a.descriptions == "extended";
  config.min_reliability = a.min_reliability;
  config.seed = a.seed;
  config.realism = realism;
  s.settings = rig::derive_settings(config, s.survey.sigma);
  return s;
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

json survey_json(const rig::Survey& s) {
  json j = {{"method", s.method}, {"sigma", s.sigma}, {"rms_error", s.rms_error}, {"max_error", s.max_error}};
  if (s.session) {
    j["realism"] = s.realism;
    j["plate_held_out_rms"] = s.session->plate_held_out_mm.rms;
    j["centroid_lean_held_out_px"] = s.session->bias_held_out_px.rms;
    j["calibration_held_out_rms"] = s.session->calibration.report.held_out.rms;
    j["board_thickness"] = s.session->plane_height;
  }
  return j;
}

std::string survey_line(const rig::Survey& s) {
  return fmt::format(
      "survey: {}, position sd {:.4f} mm as the map-maker is told; against the truth RMS {:.4f} mm, max {:.4f} mm",
      s.method == "global_camera" ? fmt::format("global camera ({} realism) + calibration", s.realism)
                                  : std::string("Gaussian error"),
      s.sigma, s.rms_error, s.max_error);
}

// "TRAJP 47 -> 75": the step a journey first went wrong at, for grouping failures by kind.
std::string step_name(const mm::RouteStep& step) {
  return fmt::format("{} {} -> {}", mm::step_description(step.step), step.step.from.object, step.step.landmark);
}

// Each planned step's kind, rated reliability and verifiability, for fitting and checking the
// forecast journey by journey.
json steps_json(const mm::Route& route) {
  json steps = json::array();
  for (const mm::RouteStep& s : route.steps) {
    steps.push_back({{"step", step_name(s)},
                     {"R", s.step.reliability},
                     {"forecast", s.step.forecast},
                     {"check", mm::verifiability_name(s.check.kind)}});
  }
  return steps;
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
              {"survey", survey_json(s.survey)},
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

int trials(const NavArgs& a, const Setup& s) {
  const auto system = rig::make_park_kender(s.survey, s.settings, *mm::parse_criterion(a.cost));
  const std::vector<std::unique_ptr<rig::Plan>> plans =
      rig::draw_plans(*system, s.world.objects.size(), *a.trials, a.seed);
  ProgressBar bar("nav", *a.trials, true);
  const rig::TrialsSummary t = rig::run_trials(*system, plans, s.world, s.settings.journey, a.threads,
                                               [&](std::int64_t done) { bar.update(done); });
  bar.clear();
  // Rates are over the journeys run: a refused plan is not a failure, it is counted apart.
  const std::int64_t asked = std::ssize(t.trials);
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  const double fps = t.seconds > 0 ? static_cast<double>(t.frames) / t.seconds : 0;
  const double mean_travel = t.true_travel / static_cast<double>(n);
  const double mean_commanded = t.commanded_travel / static_cast<double>(n);
  const double mean_planned = t.mean_planned_reliability();
  // Recoveries by kind: the map's QOC rules, and returns to an earlier landmark for another choice.
  std::int64_t backtracks = 0;
  std::int64_t rule_recoveries = 0;
  for (const rig::TrialRecord& r : t.trials) {
    backtracks += r.backtracks;
    rule_recoveries += r.recoveries - r.backtracks;
  }
  double mean_planned_distance = 0;
  for (const auto& p : plans)
    if (p->refused.empty()) mean_planned_distance += p->planned_distance / static_cast<double>(n);
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
    json outcomes;
    json rates;
    json ci;
    for (const rig::Outcome o : rig::kOutcomes) {
      const std::string name(rig::outcome_name(o));
      outcomes[name] = t.count(o);
      rates[name] = static_cast<double>(t.count(o)) / static_cast<double>(n);
      const rig::Interval w = rig::wilson_interval(t.count(o), n);
      ci[name] = {w.low, w.high};
    }
    const rig::Interval reached = rig::wilson_interval(t.reached(), n);
    // Every journey, so a failure can be replayed alone: its pair with --from/--to (the arm and
    // camera noise of a single journey differ: they are seeded by --seed, not by the trial index).
    json journeys = json::array();
    for (std::size_t i = 0; i < t.trials.size(); ++i) {
      const rig::TrialRecord& r = t.trials[i];
      const mm::Route& route = rig::route_of(*plans[i]);
      journeys.push_back({{"from", r.from},
                          {"to", r.to},
                          {"planned_reliability", r.planned_reliability},
                          {"outcome", r.refused ? "refused" : rig::outcome_name(r.outcome)},
                          {"reason", r.reason},
                          {"first_wrong_entry", r.first_wrong_entry ? json(*r.first_wrong_entry) : json(nullptr)},
                          {"first_wrong_step", r.first_wrong_entry && *r.first_wrong_entry > 0
                                                   ? json(step_name(route.steps.at(*r.first_wrong_entry - 1)))
                                                   : json(nullptr)},
                          {"steps", steps_json(route)},
                          {"recoveries", r.recoveries},
                          {"backtracks", r.backtracks},
                          {"frames", r.frames},
                          {"arm_travel", r.true_travel}});
    }
    const json j = {{"trials", asked},
                    {"run", t.run()},
                    {"refused", t.refused},
                    {"min_reliability", a.min_reliability},
                    {"outcomes", outcomes},
                    {"rates", rates},
                    {"ci95", ci},
                    {"reached_goal", t.reached()},
                    {"reached_goal_rate", static_cast<double>(t.reached()) / static_cast<double>(n)},
                    {"reached_goal_ci95", {reached.low, reached.high}},
                    {"frames", t.frames},
                    {"seconds", t.seconds},
                    {"frames_per_second", fps},
                    {"mean_arm_travel", mean_travel},
                    {"mean_commanded_travel", mean_commanded},
                    {"cost", a.cost},
                    {"survey", survey_json(s.survey)},
                    {"sigma_map", s.survey.sigma},
                    {"mean_planned_reliability", mean_planned},
                    {"mean_planned_distance", mean_planned_distance},
                    {"recoveries", {{"qoc_rules", rule_recoveries}, {"backtracks", backtracks}}},
                    {"sigma_move", a.sigma_move},
                    {"sigma_rot", a.sigma_rot},
                    {"window", a.window},
                    {"recovery", !a.no_recovery},
                    {"navigator", a.navigator},
                    {"descriptions", a.descriptions},
                    {"seed", a.seed},
                    {"journeys", journeys}};
    std::cout << j.dump() << '\n';
    return kExitOk;
  }
  std::cout << fmt::format(
      "{} journeys on {} ({} objects), cost {}, move {} /mm, rotation {} deg/mm, recovery {}, seed {}\n{}\n\n"
      "{:<20} {:>7} {:>8}  {}\n",
      n, a.world, s.world.objects.size(), a.cost, a.sigma_move, a.sigma_rot, a.no_recovery ? "off" : "on", a.seed,
      survey_line(s.survey), "OUTCOME", "COUNT", "RATE", "95% CI");
  const auto row = [&](std::string_view name, std::int64_t count) {
    const rig::Interval w = rig::wilson_interval(count, n);
    std::cout << fmt::format("{:<20} {:>7} {:>7.2f}%  [{:.2f}%, {:.2f}%]\n", name, count,
                             100.0 * static_cast<double>(count) / static_cast<double>(n), 100 * w.low, 100 * w.high);
  };
  for (const rig::Outcome o : rig::kOutcomes) row(rig::outcome_name(o), t.count(o));
  row("reached the goal", t.reached());
  if (a.min_reliability > 0) {
    std::cout << fmt::format("{:<20} {:>7}   of {} asked: routes forecast below R {} were not attempted\n", "refused",
                             t.refused, asked, a.min_reliability);
  }
  std::cout << fmt::format(
      "\nplanned: mean D {:.1f} mm; the map-maker forecast {:.2f}% of the journeys to reach the goal (mean R)\n"
      "recoveries: {} by the map's QOC rules, {} returns to an earlier landmark for another choice\n"
      "frames {} in {:.2f} s: {:.0f} frames/s; mean arm travel {:.1f} mm (commanded {:.1f} mm)\n",
      mean_planned_distance, 100 * mean_planned, rule_recoveries, backtracks, t.frames, t.seconds, fps, mean_travel,
      mean_commanded);
  return kExitOk;
}

}  // namespace

CLI::App* add_nav_command(CLI::App& app, NavArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "nav", "Navigator in the simulator: one journey (--from/--to) or --trials N random journeys and their outcomes");
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
  cmd->add_option("--video", a.video, "One journey: the onboard view with the blobs marked (.mp4, .avi, .mkv)");
  return cmd;
}

int nav_command(const NavArgs& a) {
  if (a.from.has_value() != a.to.has_value()) throw UsageError{"--from and --to go together"};
  if (a.from.has_value() == a.trials.has_value()) {
    throw UsageError{"give either --from I --to J (one journey) or --trials N (random journeys)"};
  }
  if (a.trials && *a.trials < 1) throw UsageError{fmt::format("--trials {}: must be at least 1", *a.trials)};
  if (a.trials && a.as_trial) throw UsageError{"--as-trial replays one journey: give --from/--to, not --trials"};
  if (!a.trials && !a.diagram.empty()) throw UsageError{"--reliability-diagram goes with --trials"};
  if (a.trials && (!a.plot.empty() || !a.video.empty())) {
    throw UsageError{"--plot and --video draw one journey: use them with --from/--to, not --trials"};
  }
  const Setup s = make_setup(a);
  if (!a.survey_csv.empty()) write_survey_csv(a.survey_csv, s);
  return a.trials ? trials(a, s) : one_journey(a, s);
}

}  // namespace neopipe::apps
