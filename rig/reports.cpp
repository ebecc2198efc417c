#include "rig/reports.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "calib/calibration.hpp"
#include "nav/mapmaker/parkway_quality.hpp"
#include "nav/mapmaker/parkways.hpp"
#include "rig/calibration_cache.hpp"
#include "rig/journey.hpp"
#include "rig/outcome.hpp"
#include "rig/park_kender.hpp"
#include "sim/realism.hpp"

namespace neopipe::rig {
namespace {

namespace mm = nav::mapmaker;
using nlohmann::json;

void check_positive(const char* option, double value) {
  if (!(value > 0) || !std::isfinite(value)) throw RequestError(fmt::format("{} {}: must be > 0 mm", option, value));
}

void check_non_negative(const char* option, double value, const char* unit) {
  if (!(value >= 0) || !std::isfinite(value))
    throw RequestError(fmt::format("{} {}: must be >= 0 {}", option, value, unit));
}

void check_member(const char* option, const std::string& value, std::initializer_list<const char*> allowed) {
  for (const char* a : allowed)
    if (value == a) return;
  std::string list;
  for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  throw RequestError(fmt::format("{} {}: must be one of {}", option, value, list));
}

mm::CostCriterion criterion_of(const std::string& cost) {
  const auto c = mm::parse_criterion(cost);
  if (!c) throw RequestError(fmt::format("--cost {}: must be one of distance, reliability, ratio, landmark", cost));
  return *c;
}

std::uint32_t object_id(const char* option, std::int64_t id) {
  if (id < 0) throw RequestError(fmt::format("{} {}: object ids start at 0", option, id));
  return static_cast<std::uint32_t>(id);
}

mm::Workspace load_workspace(const MapRequest& r) {
  if (r.world.empty() == r.blobs.empty()) throw RequestError("give exactly one of --world FILE and --blobs FILE");
  if (!r.world.empty()) {
    sim::World world;
    try {
      world = sim::load_world(r.world);
    } catch (const sim::WorldError& e) {
      throw mm::MapError(e.what());
    }
    mm::Workspace w{world.size, world.objects};
    mm::check_workspace(w, r.world);
    return w;
  }
  mm::Workspace w{r.size.value_or(Eigen::Vector2d(500, 500)), mm::read_blob_positions(r.blobs)};
  mm::check_workspace(w, r.blobs);
  return w;
}

double sigma_of(const MapRequest& r) {
  if (r.sigma) {
    if (!(*r.sigma >= 0) || !std::isfinite(*r.sigma))
      throw RequestError(fmt::format("--sigma {}: must be >= 0 mm", *r.sigma));
    return *r.sigma;
  }
  if (!r.calib.empty()) {
    // The map-maker's positions are as good as the calibration's held-out error: the larger axis.
    const calib::Calibration c = calib::load_calibration(r.calib);
    return std::max(c.report.held_out.sd.x(), c.report.held_out.sd.y());
  }
  return mm::NavigatorErrors{}.sigma;
}

const char* kind_of(const mm::Step& s) {
  if (s.slide) return "trajectory";
  if (s.seek == nav::Description::Far) return "far";
  if (s.seek == nav::Description::Near) return "near";
  return s.seek == nav::Description::Obvious ? "obvious" : "isolated";
}

json route_json(const mm::Route& route) {
  json path = json::array();
  path.push_back({{"object", route.start}, {"corner", nav::corner_name(route.start_corner)}, {"kind", "start"}});
  for (const mm::RouteStep& rs : route.steps) {
    const mm::Step& s = rs.step;
    json step = {{"object", s.landmark},
                 {"corner", &rs == &route.steps.back() ? json(nullptr) : json(nav::corner_name(s.adjust))},
                 {"kind", kind_of(s)},
                 {"from", s.from.object},
                 {"from_corner", nav::corner_name(s.from.corner)},
                 {"distance", rs.distance},
                 {"unreliability", s.unreliability()},
                 {"landmark_distance", s.landmark_distance},
                 {"visible", s.visible},
                 {"verification", mm::verifiability_name(rs.check.kind)},
                 {"qoc", rs.check.qoc}};
    if (const auto q = rs.entry.verified_quadrants()) step["quadrants"] = nav::format_quadrants(*q);
    if (s.slide) {
      step["via"] = s.via;
      step["dir"] = nav::direction_name(*s.slide);
      step["via_description"] = nav::description_name(s.seek);
    }
    path.push_back(step);
  }
  json entries = json::array();
  for (const nav::MapEntry& e : route.custom_map.entries) entries.push_back(nav::format_entry(e));
  return {{"from", route.start},
          {"to", route.goal},
          {"cost", mm::criterion_name(route.criterion)},
          {"path", path},
          {"costs",
           {{"D", route.distance},
            {"U", route.unreliability},
            {"D_over_R", route.ratio()},
            {"landmark_distance", route.landmark_distance}}},
          {"custom_map", entries},
          {"custom_map_text", nav::format_custom_map(route.custom_map)}};
}

}  // namespace

MapReport map_report(const MapRequest& r) {
  if (r.from.has_value() != r.to.has_value()) throw RequestError("--from and --to go together");
  check_positive("--window", r.window);
  check_member("--descriptions", r.descriptions, {"paper", "extended"});
  const mm::CostCriterion criterion = criterion_of(r.cost);
  if (!(r.reliable_threshold >= 0 && r.reliable_threshold <= 1))
    throw RequestError(fmt::format("--reliable-threshold {}: must be in 0..1", r.reliable_threshold));
  mm::Workspace workspace = load_workspace(r);
  const std::string origin = r.world.empty() ? r.blobs : r.world;
  if (workspace.objects.empty()) throw mm::MapError(fmt::format("{}: the world has no objects", origin));
  if (workspace.objects.size() == 1) {
    throw mm::MapError(fmt::format("{}: the world has one object; a map needs at least two", origin));
  }
  if (r.window > std::min(workspace.size.x(), workspace.size.y())) {
    throw mm::MapError(fmt::format("--window {} mm is larger than the {}x{} mm world", r.window, workspace.size.x(),
                                   workspace.size.y()));
  }
  mm::MapMakerOptions options;
  options.window = nav::WindowModel::with_side(r.window);
  if (r.margin) options.window.margin = *r.margin;
  options.errors.sigma = sigma_of(r);
  check_non_negative("--border-tolerance", r.border_tolerance, "mm");
  options.border_tolerance = r.border_tolerance;
  options.extended_descriptions = r.descriptions == "extended";
  options.errors.translation_per_mm = r.move_error;
  options.errors.rotation_per_mm = r.rotation_error * std::numbers::pi / 180;

  MapReport out;
  out.maker = std::make_unique<mm::MapMaker>(std::move(workspace), options);
  const mm::MapMaker& maker = *out.maker;
  const mm::WorldViews& views = maker.views();
  if (r.from) {
    const std::uint32_t from = object_id("--from", *r.from);
    const std::uint32_t to = object_id("--to", *r.to);
    try {
      out.route = maker.plan(from, to, criterion);
    } catch (const mm::UnreachableGoal& e) {
      out.unreachable = e.what();
    }
  }

  const auto general = mm::general_parkways(views);
  const auto obvious = mm::obvious_parkway(views);
  const auto isolated = mm::isolated_parkway(views);
  const auto& trajectories = maker.steps().trajectories();
  const mm::QualifiedParkways qualified =
      mm::qualify_parkways(mm::parkway_edge_qualities(views, options.errors), r.reliable_threshold);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(isolated.size() + trajectories.size());
  for (const mm::ParkwayEdge& e : isolated) edges.emplace_back(e.from, e.to);
  const std::size_t scc_parkways = mm::strongly_connected_components(views.object_count(), edges).size();
  for (const mm::Trajectory& t : trajectories) edges.emplace_back(t.from.object, t.to);
  const std::size_t scc_with_trajectories = mm::strongly_connected_components(views.object_count(), edges).size();

  json& j = out.json;
  j["objects"] = views.object_count();
  j["window"] = {{"side", options.window.side}, {"margin", options.window.margin}};
  j["sigma"] = options.errors.sigma;
  j["border_tolerance"] = options.border_tolerance;
  j["descriptions"] = r.descriptions;
  j["positions"] = json::array();
  for (std::uint32_t i = 0; i < views.object_count(); ++i) {
    j["positions"].push_back({views.position(i).x(), views.position(i).y()});
  }
  j["parkways"]["general"] = general;
  j["parkways"]["obvious"] = json::array();
  for (const auto& e : obvious) j["parkways"]["obvious"].push_back({e.from, nav::corner_name(e.corner), e.to});
  j["parkways"]["isolated"] = json::array();
  for (const auto& e : isolated) j["parkways"]["isolated"].push_back({e.from, nav::corner_name(e.corner), e.to});
  const auto subgraph_json = [](const mm::ParkwaySubgraph& g) {
    json sub = {{"obvious", json::array()}, {"isolated", json::array()}};
    for (const auto& e : g.obvious) sub["obvious"].push_back({e.from, nav::corner_name(e.corner), e.to});
    for (const auto& e : g.isolated) sub["isolated"].push_back({e.from, nav::corner_name(e.corner), e.to});
    return sub;
  };
  j["parkways"]["reliable"] = subgraph_json(qualified.reliable);
  j["parkways"]["reliable"]["threshold"] = r.reliable_threshold;
  j["parkways"]["detectable"] = subgraph_json(qualified.detectable);
  j["parkways"]["recoverable"] = subgraph_json(qualified.recoverable);
  j["qoc"] = json::array();
  for (std::uint32_t i = 0; i < views.object_count(); ++i) j["qoc"].push_back(views.qoc(i));
  j["trajectories"] = json::array();
  for (const mm::Trajectory& t : trajectories) {
    j["trajectories"].push_back({{"from", t.from.object},
                                 {"corner", nav::corner_name(t.from.corner)},
                                 {"via", t.via},
                                 {"dir", nav::direction_name(t.direction)},
                                 {"to", t.to},
                                 {"slide", t.slide}});
  }
  j["strongly_connected"] = {{"parkways", scc_parkways}, {"with_trajectories", scc_with_trajectories}};
  if (out.route) {
    const json planned = route_json(*out.route);
    for (const auto& [key, value] : planned.items()) j[key] = value;
  }
  if (!out.unreachable.empty()) j["unreachable"] = out.unreachable;
  return out;
}

NavSetup nav_setup(const NavRequest& a) {
  check_positive("--window", a.window);
  if (a.sigma_map) check_non_negative("--sigma-map", *a.sigma_map, "mm");
  check_non_negative("--sigma-move", a.sigma_move, "mm per mm");
  check_non_negative("--sigma-rot", a.sigma_rot, "degrees per mm");
  check_member("--realism", a.realism, {"ideal", "rig", "harsh"});
  check_member("--navigator", a.navigator, {"tracking", "paper"});
  check_member("--descriptions", a.descriptions, {"paper", "extended"});
  (void)criterion_of(a.cost);
  if (!(a.min_reliability >= 0 && a.min_reliability <= 1))
    throw RequestError(fmt::format("--min-reliability {}: must be in 0..1", a.min_reliability));
  if (a.threads < 0) throw RequestError(fmt::format("--threads {}: must be >= 0", a.threads));
  NavSetup s;
  s.world = sim::load_world(a.world);  // WorldError: one line naming the file
  if (s.world.objects.size() < 2) {
    throw mm::MapError(
        fmt::format("{}: the world has {} objects; a journey needs at least two", a.world, s.world.objects.size()));
  }
  if (a.window > std::min(s.world.size.x(), s.world.size.y())) {
    throw mm::MapError(
        fmt::format("--window {} mm is larger than the {}x{} mm world", a.window, s.world.size.x(), s.world.size.y()));
  }
  const sim::Realism realism = sim::parse_realism(a.realism);
  if (a.sigma_map) {
    s.survey = gaussian_survey(s.world, *a.sigma_map, a.seed);
  } else {
    SurveySettings survey;
    survey.camera.realism = realism;
    survey.camera.seed = a.seed;
    if (!a.no_cache) {
      survey.cache_dir =
          a.cache_dir.empty() ? CalibrationCache::default_dir() : std::optional<std::filesystem::path>(a.cache_dir);
    }
    survey.note = a.note;
    s.survey = global_camera_survey(s.world, survey);
  }
  ExperimentConfig config;
  config.window = a.window;
  config.arm = {a.sigma_move, a.sigma_rot};
  config.recovery = !a.no_recovery;
  config.slide_goals = !a.no_slide_goals;
  config.track_heading = a.navigator == "tracking";
  config.extended_descriptions = a.descriptions == "extended";
  config.min_reliability = a.min_reliability;
  config.seed = a.seed;
  config.realism = realism;
  s.settings = derive_settings(config, s.survey.sigma);
  return s;
}

json survey_json(const Survey& s) {
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

std::string step_name(const mm::RouteStep& step) {
  return fmt::format("{} {} -> {}", mm::step_description(step.step), step.step.from.object, step.step.landmark);
}

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

json trials_report_json(const NavigationSystem& system, const TrialsSummary& t) {
  const auto n = static_cast<double>(std::max<std::int64_t>(t.run(), 1));
  json report = {{"system", system.name()},
                 {"trials", std::ssize(t.trials)},
                 {"run", t.run()},
                 {"refused", t.refused},
                 {"frames", t.frames},
                 {"seconds", t.seconds},
                 {"mean_arm_travel", t.true_travel / n},
                 {"mean_commanded_travel", t.commanded_travel / n}};
  report.update(outcome_tables_json(t));
  return report;
}

json outcome_tables_json(const TrialsSummary& t) {
  // Over the journeys run: a refused plan is not a failure, it is counted apart.
  const std::int64_t n = std::max<std::int64_t>(t.run(), 1);
  json outcomes;
  json rates;
  json ci;
  for (const Outcome o : kOutcomes) {
    const std::string name(outcome_name(o));
    outcomes[name] = t.count(o);
    rates[name] = static_cast<double>(t.count(o)) / static_cast<double>(n);
    const Interval w = wilson_interval(t.count(o), n);
    ci[name] = {w.low, w.high};
  }
  const Interval reached = wilson_interval(t.reached(), n);
  return {{"outcomes", outcomes},
          {"rates", rates},
          {"ci95", ci},
          {"reached_goal", t.reached()},
          {"reached_goal_rate", static_cast<double>(t.reached()) / static_cast<double>(n)},
          {"reached_goal_ci95", {reached.low, reached.high}}};
}

TrialsReport trials_report(const NavRequest& a, const NavSetup& s, std::int64_t trials,
                           const std::function<void(std::int64_t)>& progress, const std::optional<TrialShard>& shard) {
  if (trials < 1) throw RequestError(fmt::format("--trials {}: must be at least 1", trials));
  const auto system = make_park_kender(s.survey, s.settings, criterion_of(a.cost));
  TrialsReport out;
  out.plans = draw_plans(*system, s.world.objects.size(), trials, a.seed);
  // A shard runs journeys first..last-1 of the same plans, seeded by their index in the whole run.
  const std::int64_t first = shard ? shard->first : 0;
  const std::int64_t last = shard ? shard->last : trials;
  std::vector<std::unique_ptr<Plan>> mine(std::make_move_iterator(out.plans.begin() + first),
                                          std::make_move_iterator(out.plans.begin() + last));
  out.summary = run_trials(*system, mine, s.world, s.settings.journey, a.threads, progress, first);
  std::move(mine.begin(), mine.end(), out.plans.begin() + first);
  const TrialsSummary& t = out.summary;
  // Every journey, so a failure can be replayed alone: its pair with --from/--to (the arm and
  // camera noise of a single journey differ: they are seeded by --seed, not by the trial index).
  // The raw fields commanded_travel and planned_distance feed the totals (trials_json removes them).
  json journeys = json::array();
  for (std::size_t i = 0; i < t.trials.size(); ++i) {
    const TrialRecord& r = t.trials[i];
    const Plan& plan = *out.plans[static_cast<std::size_t>(first) + i];
    const mm::Route& route = route_of(plan);
    journeys.push_back({{"from", r.from},
                        {"to", r.to},
                        {"planned_reliability", r.planned_reliability},
                        {"outcome", r.refused ? "refused" : outcome_name(r.outcome)},
                        {"reason", r.reason},
                        {"first_wrong_entry", r.first_wrong_entry ? json(*r.first_wrong_entry) : json(nullptr)},
                        {"first_wrong_step", r.first_wrong_entry && *r.first_wrong_entry > 0
                                                 ? json(step_name(route.steps.at(*r.first_wrong_entry - 1)))
                                                 : json(nullptr)},
                        {"steps", steps_json(route)},
                        {"recoveries", r.recoveries},
                        {"backtracks", r.backtracks},
                        {"frames", r.frames},
                        {"arm_travel", r.true_travel},
                        {kJourneyCommandedTravel, r.commanded_travel},
                        {kJourneyPlannedDistance, plan.planned_distance}});
  }
  const json config = {{"min_reliability", a.min_reliability},
                       {"cost", a.cost},
                       {"survey", survey_json(s.survey)},
                       {"sigma_map", s.survey.sigma},
                       {"sigma_move", a.sigma_move},
                       {"sigma_rot", a.sigma_rot},
                       {"window", a.window},
                       {"recovery", !a.no_recovery},
                       {"slide_goals", !a.no_slide_goals},
                       {"navigator", a.navigator},
                       {"descriptions", a.descriptions},
                       {"seed", a.seed}};
  // Rates are over the journeys run: a refused plan is not a failure, it is counted apart.
  out.json = shard ? trials_shard_json(config, journeys, *shard, t.seconds)
                   : trials_json(config, std::move(journeys), t.seconds);
  return out;
}

}  // namespace neopipe::rig
