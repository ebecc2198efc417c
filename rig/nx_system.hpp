#pragma once
// NX (qualnav.md §9) as the rig runs it. NX knows nothing beforehand: the system first lets it
// explore the world (explore_world: a station with the range ring, the start seeded, a budget of
// places and moves), then journeys run on the learned map.
//
// The harness's part (it holds the truth, NX never sees it): while NX explores, the harness notes
// where each new place really is, and so which three marbles are nearest it. A journey from marble
// I to marble J is then named in NX's own terms: the start is the learned place adjacent to I
// (nearest to I of those whose three nearest marbles include I), where the rig puts the tool; the
// goal is the learned place adjacent to J chosen the same way, plus J's compass bearing from it.
// NX travels there by its map and claims J at the surface point it measures in that bearing, and
// the rig judges the claim like any other system's. A pair with no learned place adjacent to I or
// J, or no route between them on the learned map, is unreachable.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "nav/nx/explorer.hpp"
#include "nav/nx/journey.hpp"
#include "nav/nx/learned_map.hpp"
#include "rig/navigation_system.hpp"
#include "rig/station.hpp"
#include "rig/trials.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

struct NxSettings {
  std::uint64_t seed = 1;     ///< the exploration's start and its sensor and arm noise
  double range_error = 0.10;  ///< the range ring's relative error bound (0: off)
  ArmErrors arm;              ///< the arm's errors while exploring
  nav::nx::ExploreSettings explore;
  int goal_reads = 32;  ///< frames per look when measuring the goal marble
  /// NX approaches the goal marble to this gap before it claims it (a nearer look errs less in mm).
  double goal_approach_mm = 18;
};

/// NX's control settings for a sensor with this relative error: exact finite differences without
/// noise; wider probes and averaged looks with it.
nav::nx::NxConfig nx_config_for(double range_error);

/// What the exploration learned, and the harness's notes of the truth.
struct NxExploration {
  nav::nx::LearnedMap map;
  nav::nx::ExploreReport report;
  std::vector<Eigen::Vector2d> place_truth;                 ///< where each place really is
  std::vector<std::array<std::uint32_t, 3>> place_marbles;  ///< its three nearest marbles
  std::vector<Eigen::Vector2d> track;                       ///< the tool's true track
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  std::size_t tour_places = 0;
  std::size_t tour_paths = 0;
  int tour_boundary_relations = 0;
  double seconds = 0;
};

/// Explores `world` from a seeded start clear of the marbles. `progress` gets the places found.
/// Throws std::invalid_argument for a world of fewer than three marbles.
NxExploration explore_world(const sim::World& world, const NxSettings& settings,
                            const std::function<void(std::size_t)>& progress = {});

struct NxPlan final : Plan {
  std::size_t start_place = 0;
  std::size_t goal_place = 0;
  double goal_bearing_deg = 0;     ///< J's compass bearing from the goal place
  std::vector<std::size_t> route;  ///< learned places, start first
};

/// The NX plan inside `plan`. Throws std::invalid_argument for another system's plan.
const NxPlan& nx_plan(const Plan& plan);

class NxSystem final : public NavigationSystem {
 public:
  /// `world` must outlive the system.
  NxSystem(const sim::World& world, NxExploration exploration, const NxSettings& settings);

  [[nodiscard]] std::string name() const override { return "nx"; }
  [[nodiscard]] CameraRequest camera() const override;
  [[nodiscard]] std::unique_ptr<Plan> plan(std::uint32_t from, std::uint32_t to) const override;
  /// Travel::details holds the nav::nx::NxJourney.
  Travel travel(const Plan& plan, Equipment& equipment, Witness& witness) const override;

  [[nodiscard]] const NxExploration& exploration() const { return exploration_; }
  [[nodiscard]] const NxSettings& settings() const { return settings_; }

 private:
  [[nodiscard]] std::optional<std::size_t> place_next_to(std::uint32_t marble) const;

  const sim::World& world_;
  NxExploration exploration_;
  NxSettings settings_;
};

/// The trials JSON of `neopipe nav --system nx --trials N --json`: the keys of the other systems'
/// (rig::outcome_tables_json) and NX's own ("nx": endings, legs, relocalisations, the exploration).
nlohmann::json nx_trials_json(const NxSystem& system, const std::vector<std::unique_ptr<Plan>>& plans,
                              const TrialsSummary& summary);

/// The exploration as JSON (places, edges, the budget's ending, TOUR's counts).
nlohmann::json nx_exploration_json(const NxExploration& e);

}  // namespace neopipe::rig
