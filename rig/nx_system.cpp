#include "rig/nx_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "nav/tour/cognitive_map.hpp"
#include "rig/reports.hpp"
#include "rig/seeds.hpp"
#include "sim/random.hpp"
#include "sim/range_ring.hpp"

namespace neopipe::rig {
namespace {

namespace nx = nav::nx;
using Eigen::Vector2d;
using nlohmann::json;

// NX's own random streams of the experiment seed (rig/seeds.hpp numbers the rig's; these are far
// from them and from QRM's): the exploration's start, its station's noise.
constexpr std::uint64_t kNxStartStream = 300;
constexpr std::uint64_t kNxStationStream = 301;
// The exploration starts at least this far from every marble's surface, and this far inside the
// world's edges (the sensor must see marbles around it).
constexpr double kNxStartClearanceMm = 15;
constexpr double kNxStartInsetMm = 40;

void check_nx_marbles(const sim::World& world) {
  if (world.objects.size() < 3) {
    throw std::invalid_argument(fmt::format(
        "NX needs at least three marbles (a place is equidistant from three); the world has {}", world.objects.size()));
  }
}

std::array<std::uint32_t, 3> three_nearest(const sim::World& world, const Vector2d& p) {
  std::vector<std::uint32_t> ids(world.objects.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
  std::partial_sort(ids.begin(), ids.begin() + 3, ids.end(), [&](std::uint32_t a, std::uint32_t b) {
    const double da = (world.objects[a] - p).squaredNorm();
    const double db = (world.objects[b] - p).squaredNorm();
    return da != db ? da < db : a < b;
  });
  return {ids[0], ids[1], ids[2]};
}

// Records where each new place really is (the harness's notes).
class TruthNotes final : public nx::ExploreObserver {
 public:
  TruthNotes(const Station& station, NxExploration& out, const std::function<void(std::size_t)>& progress)
      : station_(station), out_(out), progress_(progress) {}
  void place_found(std::size_t place) override {
    const Vector2d p(station_.tool().x, station_.tool().y);
    if (out_.place_truth.size() <= place) out_.place_truth.resize(place + 1);
    out_.place_truth[place] = p;
    if (progress_) progress_(place + 1);
  }

 private:
  const Station& station_;
  NxExploration& out_;
  const std::function<void(std::size_t)>& progress_;
};

Vector2d exploration_start(const sim::World& world, std::uint64_t seed) {
  sim::Random random(seed);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    Vector2d p(random.uniform(kNxStartInsetMm, world.size.x() - kNxStartInsetMm),
               random.uniform(kNxStartInsetMm, world.size.y() - kNxStartInsetMm));
    if (sim::keeps_clear(world, p, kNxStartClearanceMm)) return p;
  }
  throw std::invalid_argument("no start for the exploration clear of the marbles");
}

Ending nx_ending(nx::JourneyEnding e) {
  switch (e) {
    case nx::JourneyEnding::arrived:
      return Ending::arrived;
    case nx::JourneyEnding::blocked:
      return Ending::unrecoverable;
    default:
      return Ending::lost;
  }
}

}  // namespace

nx::NxConfig nx_config_for(double range_error) {
  nx::NxConfig c;
  c.range_error = range_error;
  // The arm repeats a move to 0.05 mm (sd), whatever its length: a climb to 0.05 mm never settles,
  // and a short probe reads the gradient off. 1.5 mm and 0.15 mm: of probes 1-4 mm and tolerances
  // 0.05-0.3 mm tried on w100_1 and w30_1 (docs/nx.md), a pair whose journeys reached the goal
  // often on both and whose exploration of the tests' exact small world makes no duplicate place.
  c.probe_mm = 1.5;
  c.place_tolerance_mm = 0.15;
  if (range_error > 0) {
    // Averaging n looks divides the error's sd by √n; a wider probe divides the gradient's by h.
    // (3 mm and 128 frames: of probes 3, 5, 8 mm and 32 or 128 frames, the only pairs that explored
    // 40 places of w100_1 at 10 % without getting lost were 3 and 5 mm with 128 frames.)
    c.probe_mm = 3;
    c.reads = 128;
    c.place_tolerance_mm = 0.3;
    c.max_climb_steps = 15;
  }
  return c;
}

NxExploration explore_world(const sim::World& world, const NxSettings& settings,
                            const std::function<void(std::size_t)>& progress) {
  check_nx_marbles(world);
  const auto t0 = std::chrono::steady_clock::now();
  NxExploration out;
  out.start = exploration_start(world, stream_seed(settings.seed, kNxStartStream));
  StationSettings s;
  s.motion = motion_errors(settings.arm);
  s.seed = stream_seed(settings.seed, kNxStationStream);
  sim::RangeRingSettings ring;
  ring.relative_error = settings.range_error;
  s.range_ring = ring;
  Station station(world, s, sim::Pose2{out.start.x(), out.start.y(), 0});
  nx::Robot robot(station.camera(), *station.compass(), station.arm(), nx_config_for(settings.range_error));
  nav::tour::TourSettings tour_settings;
  tour_settings.turn_tolerance_deg = 20;  // NX's reversals along an edge are turns around
  nav::tour::CognitiveMap tour(tour_settings);
  TruthNotes notes(station, out, progress);
  out.report = nx::explore(robot, out.map, settings.explore, &tour, &notes);
  out.place_truth.resize(out.map.size());
  for (const Vector2d& p : out.place_truth) out.place_marbles.push_back(three_nearest(world, p));
  out.track = station.log().track;
  out.tour_places = tour.places().size();
  out.tour_paths = tour.paths().size();
  for (const nav::tour::PathId path : tour.paths()) {
    for (const nav::tour::PlaceId place : tour.places()) {
      out.tour_boundary_relations += (tour.in_left(place, path) ? 1 : 0) + (tour.in_right(place, path) ? 1 : 0);
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

const NxPlan& nx_plan(const Plan& plan) {
  const auto* p = dynamic_cast<const NxPlan*>(&plan);
  if (p == nullptr) throw std::invalid_argument("not a plan of the NX system");
  return *p;
}

NxSystem::NxSystem(const sim::World& world, NxExploration exploration, const NxSettings& settings)
    : world_(world), exploration_(std::move(exploration)), settings_(settings) {
  check_nx_marbles(world);
}

CameraRequest NxSystem::camera() const {
  CameraRequest r;
  r.sensor = Sensor::range_ring;
  r.range_error = settings_.range_error;
  return r;
}

std::optional<std::size_t> NxSystem::place_next_to(std::uint32_t marble) const {
  std::optional<std::size_t> best;
  double best_d = 0;
  for (std::size_t p = 0; p < exploration_.place_marbles.size(); ++p) {
    const auto& m = exploration_.place_marbles[p];
    if (std::find(m.begin(), m.end(), marble) == m.end()) continue;
    const double d = (exploration_.place_truth[p] - world_.objects[marble]).norm();
    if (!best || d < best_d) {
      best = p;
      best_d = d;
    }
  }
  return best;
}

std::unique_ptr<Plan> NxSystem::plan(std::uint32_t from, std::uint32_t to) const {
  const std::size_t n = world_.objects.size();
  if (from >= n || to >= n) {
    throw std::invalid_argument(fmt::format("object {} is not in the world (ids 0 to {})", std::max(from, to), n - 1));
  }
  if (from == to) throw std::invalid_argument(fmt::format("the start and the goal are both object {}", from));
  const auto start = place_next_to(from);
  const auto goal = place_next_to(to);
  if (!start || !goal) {
    throw UnreachableGoal(fmt::format("NX learned no place next to object {}", start ? to : from));
  }
  auto p = std::make_unique<NxPlan>();
  p->start = from;
  p->goal = to;
  p->landmarks = {from, to};
  p->start_place = *start;
  p->goal_place = *goal;
  p->route.push_back(*start);
  double length = 0;
  for (const nx::Leg& leg : exploration_.map.route(*start, *goal)) {
    const nx::Slot& s = exploration_.map.place(leg.place).slots.at(static_cast<std::size_t>(leg.slot));
    p->route.push_back(s.to_place);
    length += s.length;
  }
  if (p->route.back() != *goal) {
    throw UnreachableGoal(fmt::format("NX's map has no route from object {}'s place to object {}'s", from, to));
  }
  const Vector2d d = world_.objects[to] - exploration_.place_truth[*goal];
  p->goal_bearing_deg = std::atan2(d.y(), d.x()) * 180 / std::numbers::pi;
  p->start_offset = exploration_.place_truth[*start] - world_.objects[from];
  p->planned_distance = length;
  return p;
}

Travel NxSystem::travel(const Plan& plan, Equipment& equipment, Witness& witness) const {
  const NxPlan& p = nx_plan(plan);
  Travel t;
  if (equipment.compass == nullptr) {
    t.ending = Ending::unrecoverable;
    t.reason = "NX needs the range ring's compass";
    return t;
  }
  nx::Robot robot(equipment.camera, *equipment.compass, equipment.arm, nx_config_for(settings_.range_error));
  nx::NxJourney j = nx::travel_to_place(robot, exploration_.map, p.start_place, p.goal_place);
  if (j.ending == nx::JourneyEnding::arrived) {
    const auto offset =
        nx::approach_marble(robot, p.goal_bearing_deg, settings_.goal_approach_mm, settings_.goal_reads);
    if (offset) {
      witness.landmark_claimed(1, *offset);
    } else {
      j.ending = nx::JourneyEnding::lost;
      j.reason = "no marble in the goal's bearing";
    }
  }
  t.ending = nx_ending(j.ending);
  t.reason = j.reason;
  t.recoveries = j.relocalisations + j.detours;
  t.frames = robot.frames();
  t.details = std::move(j);
  return t;
}

json nx_exploration_json(const NxExploration& e) {
  const nx::ExploreReport& r = e.report;
  return {{"ending", r.ending},
          {"places", r.places},
          {"edges", r.edges},
          {"open_edges", r.open_edges},
          {"blocked_edges", r.blocked_edges},
          {"matches", r.matches},
          {"arrivals_unlinked", r.arrivals_unlinked},
          {"moves", r.moves},
          {"frames", r.frames},
          {"travelled_mm", r.travelled_mm},
          {"tour_places", e.tour_places},
          {"tour_paths", e.tour_paths},
          {"tour_boundary_relations", e.tour_boundary_relations},
          {"seconds", e.seconds}};
}

json nx_trials_json(const NxSystem& system, const std::vector<std::unique_ptr<Plan>>& plans, const TrialsSummary& t) {
  std::array<std::int64_t, nx::kJourneyEndings> endings{};
  std::int64_t legs = 0;
  std::int64_t relocalisations = 0;
  json journeys = json::array();
  for (std::size_t i = 0; i < t.trials.size(); ++i) {
    const TrialRecord& r = t.trials[i];
    const NxPlan& plan = nx_plan(*plans[i]);
    json j = {{"from", r.from},
              {"to", r.to},
              {"outcome", outcome_name(r.outcome)},
              {"reason", r.reason},
              {"planned_places", plan.route},
              {"frames", r.frames},
              {"arm_travel", r.true_travel}};
    if (const auto* report = std::any_cast<nx::NxJourney>(&r.details)) {
      ++endings[static_cast<std::size_t>(report->ending)];
      legs += report->legs;
      relocalisations += report->relocalisations;
      j["ending"] = nx::journey_ending_name(report->ending);
      j["places"] = report->places;
      j["legs"] = report->legs;
      j["relocalisations"] = report->relocalisations;
      j["detours"] = report->detours;
    }
    journeys.push_back(std::move(j));
  }
  json own;
  for (std::size_t e = 0; e < endings.size(); ++e) {
    own[nx::journey_ending_name(static_cast<nx::JourneyEnding>(e))] = endings[e];
  }
  json report = trials_report_json(system, t);
  report["nx"] = {{"endings", own},
                  {"legs", legs},
                  {"relocalisations", relocalisations},
                  {"range_error", system.settings().range_error},
                  {"exploration", nx_exploration_json(system.exploration())}};
  report["journeys"] = std::move(journeys);
  return report;
}

}  // namespace neopipe::rig
