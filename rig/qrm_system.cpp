#include "rig/qrm_system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "nav/common/panorama_reading.hpp"
#include "nav/qrm/observation.hpp"
#include "nav/qrm/rng.hpp"
#include "rig/outcome.hpp"
#include "rig/qrm_imaging.hpp"
#include "rig/reports.hpp"
#include "rig/seeds.hpp"
#include "rig/start_placement.hpp"
#include "sim/panorama.hpp"

namespace neopipe::rig {
namespace {

namespace q = nav::qrm;
using Eigen::Vector2d;
using nlohmann::json;

// The tour's own random streams of the experiment seed (rig/seeds.hpp numbers the rig's streams;
// these are QRM's and far from them): positions, bearing noise, zero directions.
constexpr std::uint64_t kTourStream = 200;
// The start keeps this much more than kMinClearanceMm from every marble's surface, so the arm's
// first error cannot take the tool inside the clearance.
constexpr double kPlacementMarginMm = 2.5;

void check_marbles(const sim::World& world) {
  if (world.objects.size() < 3) {
    throw std::invalid_argument(
        fmt::format("QRM needs at least three marbles (triples of landmarks); the world has {}", world.objects.size()));
  }
}

Ending qrm_ending(q::NavigationEnding e) {
  switch (e) {
    case q::NavigationEnding::arrived:
      return Ending::arrived;
    case q::NavigationEnding::no_path:
    case q::NavigationEnding::target_lost:
    case q::NavigationEnding::step_limit:
      return Ending::lost;  // aware that it cannot find its way
    case q::NavigationEnding::blocked:
      return Ending::unrecoverable;
  }
  return Ending::lost;
}

// Passes the navigator's landmarks to the rig's witness: the start (entry 0) and the goal (entry
// 1), the plan's only entries. The landmarks between are the navigator's own account (its report).
class EntryRelay final : public q::NavigationObserver {
 public:
  EntryRelay(const Plan& plan, Witness& witness) : plan_(plan), witness_(witness) {}
  void landmark_reached(q::LandmarkId id, const Vector2d& offset) override {
    if (id == plan_.goal) {
      witness_.landmark_claimed(1, offset);
    } else if (id == plan_.start && first_) {
      witness_.landmark_claimed(0, offset);
    }
    first_ = false;
  }

 private:
  const Plan& plan_;
  Witness& witness_;
  bool first_ = true;
};

}  // namespace

q::RelationalMap build_map_by_tour(const sim::World& world, const QrmSettings& settings, ImagingTour* tour,
                                   const std::function<void(std::size_t)>& progress) {
  check_marbles(world);
  const auto start = std::chrono::steady_clock::now();
  QrmImagingSettings imaging;
  imaging.sensor.bearing_noise_deg = settings.bearing_noise_deg;
  imaging.sensor.seed = stream_seed(settings.seed, kTourStream + 1);
  imaging.heading_seed = stream_seed(settings.seed, kTourStream + 2);
  imaging.observation = settings.navigator.observation;
  const std::vector<Vector2d> positions =
      random_imaging_positions(world, settings.images, stream_seed(settings.seed, kTourStream));
  q::RelationalMap map;
  ImagingTour done;
  for (const QrmImageReport& r :
       qrm_imaging_tour(world, positions, imaging, map, [&](std::size_t i, const QrmImageReport&) {
         if (progress) progress(i + 1);
       })) {
    ++done.images;
    done.triples += r.fused.triples;
    done.inconsistent += r.fused.inconsistent;
  }
  done.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (tour != nullptr) *tour = done;
  return map;
}

QrmSystem::QrmSystem(const sim::World& world, q::RelationalMap map, const QrmSettings& settings)
    : world_(world), map_(std::move(map)), settings_(settings) {
  check_marbles(world);
}

CameraRequest QrmSystem::camera() const {
  CameraRequest r;
  r.sensor = Sensor::panoramic;
  r.bearing_noise_deg = settings_.bearing_noise_deg;
  return r;
}

std::unique_ptr<Plan> QrmSystem::plan(std::uint32_t from, std::uint32_t to) const {
  const std::size_t n = world_.objects.size();
  if (from >= n || to >= n) {
    throw std::invalid_argument(fmt::format("object {} is not in the world (ids 0 to {})", std::max(from, to), n - 1));
  }
  if (from == to) throw std::invalid_argument(fmt::format("the start and the goal are both object {}", from));
  if (!map_.has_landmark(from) || !map_.has_landmark(to)) {
    throw UnreachableGoal(fmt::format("the imaging tour never saw object {}", map_.has_landmark(from) ? to : from));
  }
  const std::vector<q::LandmarkId> route = q::plan_route(q::estimate_rng(map_), from, to);
  if (route.empty()) throw UnreachableGoal(fmt::format("the map's RNG estimate has no path from {} to {}", from, to));
  auto p = std::make_unique<QrmPlan>();
  p->start = from;
  p->goal = to;
  p->route = route;
  p->landmarks = {from, to};
  // The harness places the tool in the start's Voronoi cell, clear of every marble: the nearest
  // such point on rings around it, first direction first (deterministic).
  const std::optional<Vector2d> offset = clear_start_offset(world_, from, kPlacementMarginMm);
  if (!offset) throw UnreachableGoal(fmt::format("no start clear of the marbles in object {}'s cell", from));
  p->start_offset = *offset;
  // QRM has no model of how often a journey arrives: c_ij measures how uncertain an edge's RNG
  // membership is, not a probability of reaching. So no forecast is made (1), and no distance:
  // the map holds no metric.
  p->planned_reliability = 1;
  p->planned_distance = 0;
  return p;
}

Travel QrmSystem::travel(const Plan& plan, Equipment& equipment, Witness& witness) const {
  q::RelationalMap map = map_;  // the journey's own copy: journeys run in parallel
  q::RingEye eye(equipment.camera, {world_.marble_diameter / 2, settings_.bearing_noise_deg});
  EntryRelay relay(plan, witness);
  q::NavigationReport report =
      q::navigate(map, plan.goal, eye, equipment.arm, settings_.navigator, &relay, qrm_route(plan));
  Travel t;
  t.ending = qrm_ending(report.ending);
  t.reason = report.reason;
  t.recoveries = report.reroutes;  // re-plans that left the path: QRM's recovery
  t.frames = report.frames;
  t.details = std::move(report);
  return t;
}

const std::vector<q::LandmarkId>& qrm_route(const Plan& plan) {
  const auto* p = dynamic_cast<const QrmPlan*>(&plan);
  if (p == nullptr) throw std::invalid_argument("not a plan of the QRM system");
  return p->route;
}

const q::NavigationReport* qrm_report(const Travel& travel) {
  return std::any_cast<q::NavigationReport>(&travel.details);
}

json qrm_trials_json(const QrmSystem& system, const std::vector<std::unique_ptr<Plan>>& plans, const TrialsSummary& t) {
  std::array<std::int64_t, q::kNavigationEndings> endings{};
  std::int64_t steps = 0;
  std::int64_t detours = 0;
  std::int64_t reroutes = 0;
  std::int64_t images = 0;
  std::int64_t inconsistent = 0;
  json journeys = json::array();
  for (std::size_t i = 0; i < t.trials.size(); ++i) {
    const TrialRecord& r = t.trials[i];
    const auto* report = std::any_cast<q::NavigationReport>(&r.details);
    json j = {{"from", r.from},
              {"to", r.to},
              {"outcome", outcome_name(r.outcome)},
              {"reason", r.reason},
              {"planned_route", qrm_route(*plans[i])},
              {"first_wrong_entry", r.first_wrong_entry ? json(*r.first_wrong_entry) : json(nullptr)},
              {"frames", r.frames},
              {"arm_travel", r.true_travel}};
    if (report != nullptr) {
      ++endings[static_cast<std::size_t>(report->ending)];
      steps += report->steps;
      detours += report->detours;
      reroutes += report->reroutes;
      images += report->images_fused;
      inconsistent += static_cast<std::int64_t>(report->inconsistent);
      j["ending"] = q::navigation_ending_name(report->ending);
      j["reached"] = report->reached;
      j["steps"] = report->steps;
      j["detours"] = report->detours;
      j["reroutes"] = report->reroutes;
      j["images_fused"] = report->images_fused;
    }
    journeys.push_back(std::move(j));
  }
  json own;
  for (std::size_t e = 0; e < endings.size(); ++e) {
    own[std::string(q::navigation_ending_name(static_cast<q::NavigationEnding>(e)))] = endings[e];
  }
  const QrmSettings& s = system.settings();
  json report = trials_report_json(system, t);
  report["qrm"] = {{"endings", own},
                   {"steps", steps},
                   {"detours", detours},
                   {"reroutes", reroutes},
                   {"images_fused", images},
                   {"inconsistent_measurements", inconsistent},
                   {"images", s.images},
                   {"k", s.navigator.observation.nearest},
                   {"step_mm", s.navigator.step_mm},
                   {"fuse_every", s.navigator.fuse_every},
                   {"max_steps", s.navigator.max_steps},
                   {"map_landmarks", system.map().size()}};
  report["journeys"] = std::move(journeys);
  return report;
}

}  // namespace neopipe::rig
