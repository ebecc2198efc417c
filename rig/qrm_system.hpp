#pragma once
// The qualitative relational map's system (spec qrm.md §8, §9) as the rig runs it. Before any
// journey the robot's map is built by an imaging tour at positions the harness chooses; plan()
// routes by Dijkstra over the RNG estimated from that map; travel() hands the navigator
// (nav/qrm/navigator) a copy of the map, the panoramic sensor's ring images and the arm, and passes
// on to the rig each landmark of the plan it believes it holds.
//
// The system holds the world's true positions for the harness's two jobs only: choosing imaging
// positions and placing the tool at the start (Plan::start_offset). The navigator never sees them.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "nav/qrm/navigator/navigator.hpp"
#include "nav/qrm/relational_map.hpp"
#include "rig/navigation_system.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

struct QrmSettings {
  std::size_t images = 30;              ///< imaging positions of the tour that builds the map
  std::uint64_t seed = 1;               ///< the tour's positions, headings and sensor noise
  double bearing_noise_deg = 0;         ///< the panoramic sensor's configured noise
  nav::qrm::NavigatorConfig navigator;  ///< its observation.nearest is k, for the tour too
};

/// What the imaging tour did.
struct ImagingTour {
  std::size_t images = 0;
  std::size_t triples = 0;       ///< measurements fused
  std::size_t inconsistent = 0;  ///< of them rolled back
  double seconds = 0;
};

/// The map of `world` built by the imaging tour (rig/qrm_imaging.hpp) at `settings.images` random
/// positions clear of the marbles, each ring at a random zero direction, read by the engine's
/// panorama graph, its k nearest (not partly hidden) sightings fused. `progress` gets the images done.
/// Throws std::invalid_argument for a world of fewer than three marbles.
nav::qrm::RelationalMap build_map_by_tour(const sim::World& world, const QrmSettings& settings,
                                          ImagingTour* tour = nullptr,
                                          const std::function<void(std::size_t)>& progress = {});

/// A QRM journey. Plan::landmarks is {start, goal}: the route is re-planned as the map improves
/// (spec §8), so its intermediate landmarks are no fixed entries the rig could hold the navigator
/// to; the rig judges the start and, above all, the landmark the navigator believes is the goal.
/// Leaving the planned route counts as a recovery (Travel::recoveries: re-routes).
struct QrmPlan final : Plan {
  std::vector<nav::qrm::LandmarkId> route;  ///< planned on the built map, start first
};

/// The route of a plan made by a QrmSystem. Throws std::invalid_argument for another plan.
const std::vector<nav::qrm::LandmarkId>& qrm_route(const Plan& plan);

class QrmSystem final : public NavigationSystem {
 public:
  /// `world` must outlive the system. Throws std::invalid_argument for fewer than three marbles.
  QrmSystem(const sim::World& world, nav::qrm::RelationalMap map, const QrmSettings& settings);

  [[nodiscard]] std::string name() const override { return "qrm"; }
  [[nodiscard]] CameraRequest camera() const override;
  /// Dijkstra on the built map's RNG estimate. Throws UnreachableGoal when it has no path (or the
  /// tour never saw one of the two), std::invalid_argument for an unknown id or from == to.
  [[nodiscard]] std::unique_ptr<Plan> plan(std::uint32_t from, std::uint32_t to) const override;
  /// Travel::details holds the navigator's nav::qrm::NavigationReport.
  Travel travel(const Plan& plan, Equipment& equipment, Witness& witness) const override;

  [[nodiscard]] const nav::qrm::RelationalMap& map() const { return map_; }
  [[nodiscard]] const QrmSettings& settings() const { return settings_; }

 private:
  const sim::World& world_;
  nav::qrm::RelationalMap map_;
  QrmSettings settings_;
};

/// The navigator's report of a journey run by a QrmSystem, or null.
const nav::qrm::NavigationReport* qrm_report(const Travel& travel);

/// The trials JSON of `neopipe nav --system qrm --trials N --json`: the keys Park & Kender's has
/// (trials, outcomes, rates, reached_goal, reached_goal_rate, reached_goal_ci95, ...) and the
/// navigator's own endings ("qrm": {"endings": {...}, ...}), journey by journey.
/// Rates are over the journeys run.
nlohmann::json qrm_trials_json(const QrmSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                               const TrialsSummary& summary);

}  // namespace neopipe::rig
