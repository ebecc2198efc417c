#include "rig/qualnav_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "nav/common/panorama_reading.hpp"
#include "nav/qualnav/navigator/view_source.hpp"
#include "rig/reports.hpp"
#include "rig/seeds.hpp"
#include "rig/start_placement.hpp"
#include "sim/panorama.hpp"
#include "sim/random.hpp"

namespace neopipe::rig {
namespace {

namespace qn = nav::qualnav;
using Eigen::Vector2d;
using nlohmann::json;

// Qualnav's own random streams of the experiment seed, far from the rig's and QRM's.
constexpr std::uint64_t kRecordingStream = 300;
constexpr std::uint64_t kJourneyRangeStream = 301;
// The start keeps this much more than the robot's clearance from every marble's surface.
constexpr double kQualnavStartMarginMm = 5;

Ending qualnav_ending(qn::NavigationEnding e) {
  switch (e) {
    case qn::NavigationEnding::arrived:
      return Ending::arrived;
    case qn::NavigationEnding::no_memory:
    case qn::NavigationEnding::lost:
    case qn::NavigationEnding::goal_lost:
    case qn::NavigationEnding::step_limit:
      return Ending::lost;
    case qn::NavigationEnding::blocked:
      return Ending::unrecoverable;
  }
  return Ending::lost;
}

// Passes the navigator's goal to the rig's witness as the plan's last entry.
class GoalRelay final : public qn::GoalObserver {
 public:
  GoalRelay(const Plan& plan, Witness& witness) : plan_(plan), witness_(witness) {}
  void goal_held(const Vector2d& offset) override { witness_.landmark_claimed(plan_.landmarks.size() - 1, offset); }

 private:
  const Plan& plan_;
  Witness& witness_;
};

}  // namespace

std::string_view qualnav_level_name(QualnavLevel level) {
  return level == QualnavLevel::regions ? "regions" : "viewframes";
}

json qualnav_region_json(const qn::RegionLevelCounters& c) {
  return {{"ending", c.ending},
          {"plan_regions", c.plan_regions},
          {"regions_crossed", c.regions_crossed},
          {"shortcuts", c.shortcuts},
          {"production_steps", c.production_steps},
          {"fallback_steps", c.fallback_steps},
          {"fallbacks", c.fallbacks},
          {"steps", c.steps},
          {"path_mm", c.path_mm}};
}

const QualnavPlan& qualnav_plan(const Plan& plan) {
  const auto* p = dynamic_cast<const QualnavPlan*>(&plan);
  if (p == nullptr) throw std::invalid_argument("not a plan of the Qualnav system");
  return *p;
}

QualnavSystem::QualnavSystem(const sim::World& world, const QualnavSettings& settings)
    : world_(world), settings_(settings) {
  if (world.objects.size() < 2) {
    throw std::invalid_argument(fmt::format(
        "Qualnav needs at least two marbles (a pair to localize by); the world has {}", world.objects.size()));
  }
  if (!(settings.sensing.range_error >= 0) || !std::isfinite(settings.sensing.range_error)) {
    throw std::invalid_argument(
        fmt::format("range error {}: must be finite and not negative", settings.sensing.range_error));
  }
  settings_.navigator.clearance.marble_radius_mm = world.marble_diameter / 2;
}

CameraRequest QualnavSystem::camera() const {
  CameraRequest r;
  r.sensor = Sensor::panoramic;
  r.bearing_noise_deg = settings_.sensing.bearing_noise_deg;
  return r;
}

std::unique_ptr<Plan> QualnavSystem::plan(std::uint32_t from, std::uint32_t to) const {
  const std::size_t n = world_.objects.size();
  if (from >= n || to >= n) {
    throw std::invalid_argument(fmt::format("object {} is not in the world (ids 0 to {})", std::max(from, to), n - 1));
  }
  if (from == to) throw std::invalid_argument(fmt::format("the start and the goal are both object {}", from));
  auto p = std::make_unique<QualnavPlan>();
  p->start = from;
  p->goal = to;
  p->landmarks = {from, to};
  // The start: the nearest point clear of every marble in the start's cell, first direction first.
  const std::optional<Vector2d> offset = clear_start_offset(world_, from, kQualnavStartMarginMm);
  if (!offset) throw UnreachableGoal(fmt::format("no start clear of the marbles in object {}'s cell", from));
  p->start_offset = *offset;
  const Vector2d start = world_.objects[from] + p->start_offset;
  auto route = settings_.detour ? teach_detour(world_, start, to, settings_.route_clearance_mm, settings_.route_end_mm,
                                               (from + to) % 2 == 0 ? 1.0 : -1.0)
                                : teach_route(world_, start, to, settings_.route_clearance_mm, settings_.route_end_mm);
  if (!route) {
    throw UnreachableGoal(fmt::format("no route from object {} to {} keeps {} mm from the marbles", from, to,
                                      settings_.route_clearance_mm));
  }
  p->route = std::move(*route);
  p->seed = stream_seed(stream_seed(settings_.seed, kRecordingStream), static_cast<std::uint64_t>(from) * n + to);
  auto memory = std::make_shared<qn::VisualMemory>();
  memory->add_viewpath(
      record_viewpath(world_, sample_route(p->route, qn::kViewpathSpacingMm), settings_.sensing, p->seed));
  p->memory = std::move(memory);
  p->planned_distance = route_length(p->route);
  p->planned_reliability = 1;  // Qualnav makes no forecast
  return p;
}

Travel QualnavSystem::travel(const Plan& plan, Equipment& equipment, Witness& witness) const {
  const QualnavPlan& p = qualnav_plan(plan);
  Travel t;
  if (equipment.compass == nullptr) {
    t.ending = Ending::unrecoverable;
    t.reason = "Qualnav needs the panoramic sensor's compass";
    return t;
  }
  // The range error of this journey's sightings: a stream of the plan's seed and the first compass
  // reading, which carries this journey's noise (the Equipment has no seed of its own).
  const double first_compass = equipment.compass->read().heading_deg;
  sim::Random range_noise(
      stream_seed(stream_seed(p.seed, kJourneyRangeStream), std::bit_cast<std::uint64_t>(first_compass)));
  const double e = settings_.sensing.range_error;
  qn::RingViewSource eye(
      equipment.camera, *equipment.compass,
      nav::PanoramaModel{world_.marble_diameter / 2, settings_.sensing.bearing_noise_deg}, qualnav_interval_factor(e),
      [&](std::vector<nav::PanoramaSighting>& s) { apply_range_error(s, e, [&] { return range_noise.uniform(); }); });
  GoalRelay relay(plan, witness);
  qn::NavigationReport report =
      settings_.level == QualnavLevel::regions
          ? qn::navigate_regions(*p.memory, plan.goal, eye, equipment.arm, settings_.navigator, settings_.regions,
                                 &relay)
          : qn::navigate(*p.memory, plan.goal, eye, equipment.arm, settings_.navigator, &relay);
  t.ending = qualnav_ending(report.ending);
  t.reason = report.reason;
  t.recoveries = report.shortcuts;  // leaving the remembered path for a shortcut
  t.frames = eye.frames();
  t.details = std::move(report);
  return t;
}

const qn::NavigationReport* qualnav_report(const Travel& travel) {
  return std::any_cast<qn::NavigationReport>(&travel.details);
}

json qualnav_trials_json(const QualnavSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                         const TrialsSummary& t) {
  std::array<std::int64_t, qn::kNavigationEndings> endings{};
  std::int64_t steps = 0;
  std::int64_t shortcuts = 0;
  std::int64_t detours = 0;
  double taught = 0;
  double taught_turning = 0;
  double executed_turning = 0;
  std::int64_t arrived_shorter = 0;
  std::int64_t arrived_smoother = 0;
  std::int64_t arrived = 0;
  double executed = 0;  // path moves of the journeys that arrived
  double taught_arrived = 0;
  qn::RegionLevelCounters regions;  // summed over the journeys
  std::map<std::string, std::int64_t> region_endings;
  json journeys = json::array();
  for (std::size_t i = 0; i < t.trials.size(); ++i) {
    const TrialRecord& r = t.trials[i];
    const QualnavPlan& p = qualnav_plan(*plans[i]);
    const auto* report = std::any_cast<qn::NavigationReport>(&r.details);
    const double route_mm = route_length(p.route);
    // Turning of both at the memory's 20 mm spacing, so the executed path's 10 mm steps and the
    // route's grid corners count alike.
    const double route_turn = route_turning(sample_route(p.route, qn::kViewpathSpacingMm));
    taught += route_mm;
    taught_turning += route_turn;
    json j = {{"from", r.from},
              {"to", r.to},
              {"outcome", outcome_name(r.outcome)},
              {"reason", r.reason},
              {"memory_viewframes", p.memory->nodes().size()},
              {"taught_route_mm", route_mm},
              {"taught_turning_deg", route_turn * 180 / std::numbers::pi},
              {"frames", r.frames},
              {"arm_travel", r.true_travel}};
    if (report != nullptr) {
      ++endings[static_cast<std::size_t>(report->ending)];
      steps += report->steps;
      shortcuts += report->shortcuts;
      detours += report->detours;
      const double path_turn = route_turning(sample_route(report->path, qn::kViewpathSpacingMm));
      executed_turning += path_turn;
      if (report->ending == qn::NavigationEnding::arrived) {
        ++arrived;
        taught_arrived += route_mm;
        // The executed path against the taught route, both to where the taught route ends (the
        // executed one also makes the parallax moves and the last 5 mm to the stop).
        arrived_shorter += static_cast<std::int64_t>(report->path_mm < route_mm);
        executed += report->path_mm;
        arrived_smoother += static_cast<std::int64_t>(path_turn < route_turn);
      }
      j["ending"] = qn::navigation_ending_name(report->ending);
      j["steps"] = report->steps;
      j["heading_steps"] = report->heading_steps;
      j["approach_steps"] = report->approach_steps;
      j["shortcuts"] = report->shortcuts;
      j["replans"] = report->replans;
      j["detours"] = report->detours;
      j["commanded_travel"] = report->commanded_mm;
      j["path_turning_deg"] = path_turn * 180 / std::numbers::pi;
      j["path_mm"] = report->path_mm;
      if (report->regions.used) {
        const qn::RegionLevelCounters& c = report->regions;
        j["regions"] = qualnav_region_json(c);
        ++region_endings[c.ending];
        regions.plan_regions += c.plan_regions;
        regions.regions_crossed += c.regions_crossed;
        regions.shortcuts += c.shortcuts;
        regions.production_steps += c.production_steps;
        regions.fallback_steps += c.fallback_steps;
        regions.fallbacks += c.fallbacks;
        regions.steps += c.steps;
        regions.path_mm += c.path_mm;
      }
    }
    journeys.push_back(std::move(j));
  }
  json own;
  for (std::size_t e = 0; e < endings.size(); ++e) {
    own[std::string(qn::navigation_ending_name(static_cast<qn::NavigationEnding>(e)))] = endings[e];
  }
  const QualnavSettings& s = system.settings();
  const double runs = static_cast<double>(std::max<std::size_t>(t.trials.size(), 1));
  json report = trials_report_json(system, t);
  report["qualnav"] = {{"endings", own},
                       {"steps", steps},
                       {"shortcuts", shortcuts},
                       {"detours", detours},
                       {"range_error", s.sensing.range_error},
                       {"step_mm", s.navigator.step_mm},
                       {"route_clearance_mm", s.route_clearance_mm},
                       {"taught_routes", s.detour ? "detour" : "shortest"},
                       {"mean_taught_route_mm", taught / runs},
                       {"mean_taught_turning_deg", taught_turning / runs * 180 / std::numbers::pi},
                       {"mean_path_turning_deg", executed_turning / runs * 180 / std::numbers::pi},
                       {"arrived", arrived},
                       {"arrived_taught_route_mm", taught_arrived},
                       {"arrived_path_mm", executed},
                       {"arrived_shorter_than_taught", arrived_shorter},
                       {"arrived_smoother_than_taught", arrived_smoother},
                       {"level", qualnav_level_name(s.level)}};
  if (s.level == QualnavLevel::regions) {
    json r = qualnav_region_json(regions);
    r.erase("ending");
    r["landmarks"] = s.regions.landmarks;
    r["phase_endings"] = region_endings;
    report["qualnav"]["regions"] = std::move(r);
  }
  report["journeys"] = std::move(journeys);
  return report;
}

}  // namespace neopipe::rig
