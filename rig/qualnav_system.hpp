#pragma once
// Qualnav's system (qualnav.md §6, §7) as the rig runs it. What it knows beforehand is a visual
// memory the harness records: plan(from, to) teaches the route from the start to the goal once — as
// the Qualnav simulator's user clicked a path — (rig/qualnav_teaching.hpp) and records a viewframe
// every 20 mm along it. travel() hands the navigator (nav/qualnav/navigator) that memory, the
// panoramic sensor's ring and compass through a reading adapter that puts in the range error, and
// the arm; the navigator ends with the goal's a heading, 15 mm from it, and the system claims the goal
// (the plan's last entry) with the offset the navigator measured.
//
// The system holds the world's true positions for the harness's jobs only: teaching routes,
// recording viewpaths and placing the tool at the start. The navigator never sees them.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "nav/qualnav/metric/visual_memory.hpp"
#include "nav/qualnav/navigator/navigator.hpp"
#include "nav/qualnav/navigator/region_level.hpp"
#include "rig/navigation_system.hpp"
#include "rig/qualnav_teaching.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// The level a journey starts at (qualnav.md §1): viewframe headings all the way, or the orientation
/// regions first (nav/qualnav/navigator/region_level.hpp), the viewframe level finishing.
enum class QualnavLevel : std::uint8_t { viewframes, regions };
std::string_view qualnav_level_name(QualnavLevel level);

struct QualnavSettings {
  QualnavSensing sensing;          ///< range error e (0.5: the papers' 50 %) and bearing noise
  std::uint64_t seed = 1;          ///< the recordings' noise; the journeys' range errors derive from it too
  double route_clearance_mm = 14;  ///< the taught routes keep this from every marble's surface
  double route_end_mm = 20;        ///< the taught route ends this far from the goal's centre
  bool detour = false;             ///< teach roundabout routes (teach_detour) instead of the shortest
  nav::qualnav::NavigatorConfig navigator;
  QualnavLevel level = QualnavLevel::viewframes;
  nav::qualnav::RegionLevelConfig regions;  ///< the region level's, when level is regions
};

/// A Qualnav journey: entries {start, goal}; the memory recorded along the taught route.
struct QualnavPlan final : Plan {
  std::vector<Eigen::Vector2d> route;  ///< the taught route (harness truth, for plots and metrics), start first
  std::shared_ptr<const nav::qualnav::VisualMemory> memory;
  std::uint64_t seed = 0;  ///< of its recording
};

/// The plan as a QualnavPlan. Throws std::invalid_argument for another plan.
const QualnavPlan& qualnav_plan(const Plan& plan);

class QualnavSystem final : public NavigationSystem {
 public:
  /// `world` must outlive the system. Throws std::invalid_argument for fewer than two marbles or a
  /// negative range error.
  QualnavSystem(const sim::World& world, const QualnavSettings& settings);

  [[nodiscard]] std::string name() const override { return "qualnav"; }
  [[nodiscard]] CameraRequest camera() const override;
  /// Teaches the route and records its viewpath. Throws UnreachableGoal when no route keeps the
  /// clearance, std::invalid_argument for an unknown id or from == to.
  [[nodiscard]] std::unique_ptr<Plan> plan(std::uint32_t from, std::uint32_t to) const override;
  /// Travel::details holds the navigator's nav::qualnav::NavigationReport.
  Travel travel(const Plan& plan, Equipment& equipment, Witness& witness) const override;

  [[nodiscard]] const QualnavSettings& settings() const { return settings_; }

 private:
  const sim::World& world_;
  QualnavSettings settings_;
};

/// The navigator's report of a journey run by a QualnavSystem, or null.
const nav::qualnav::NavigationReport* qualnav_report(const Travel& travel);

/// What the region level did in a journey (its counters), as the JSON of one journey and of trials write it.
nlohmann::json qualnav_region_json(const nav::qualnav::RegionLevelCounters& counters);

/// The trials JSON of `neopipe nav --system qualnav --trials N --json`: the keys of the other systems'
/// (trials, outcomes, rates, reached_goal, reached_goal_rate, reached_goal_ci95, ...) and Qualnav's
/// own ("qualnav": endings, steps, shortcuts, path lengths and turning of the taught routes against
/// the executed paths), journey by journey.
nlohmann::json qualnav_trials_json(const QualnavSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                                   const TrialsSummary& summary);

}  // namespace neopipe::rig
