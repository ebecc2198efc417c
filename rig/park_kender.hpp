#pragma once
// Park & Kender's system (park-kender.md) as the rig runs it: the map-maker plans a route on the
// survey and writes its custom map; the navigator follows the map through the onboard camera and
// the arm, telling the rig each landmark it holds.

#include <memory>
#include <string>

#include "nav/mapmaker/map_maker.hpp"
#include "nav/navigator/navigator.hpp"
#include "rig/navigation_system.hpp"

namespace neopipe::rig {

/// A route and its custom map.
struct ParkKenderPlan final : Plan {
  nav::mapmaker::Route route;
};

class ParkKenderSystem final : public NavigationSystem {
 public:
  /// The map-maker over `survey` with `options`, planning by `criterion`; the navigator with
  /// `navigator` (its window must be the map-maker's). `observer`, if given, also sees every frame
  /// and landmark of the navigator (a video of one journey): then travel one journey at a time.
  ParkKenderSystem(nav::mapmaker::Workspace survey, const nav::mapmaker::MapMakerOptions& options,
                   nav::mapmaker::CostCriterion criterion, const nav::navigator::NavigatorConfig& navigator,
                   nav::navigator::Observer* observer = nullptr);

  [[nodiscard]] std::string name() const override { return "park-kender"; }
  [[nodiscard]] CameraRequest camera() const override;
  /// Throws UnreachableGoal (with the map-maker's words) when no route exists, and
  /// nav::mapmaker::MapError for unknown ids or a start equal to the goal. A route whose forecast
  /// is below refuse_below's least reliability is replaced by the most reliable one; when that too
  /// falls short the plan is marked refused (Plan::refused).
  [[nodiscard]] std::unique_ptr<Plan> plan(std::uint32_t from, std::uint32_t to) const override;
  Travel travel(const Plan& plan, Equipment& equipment, Witness& witness) const override;

  [[nodiscard]] const nav::mapmaker::MapMaker& maker() const { return maker_; }
  [[nodiscard]] const nav::navigator::NavigatorConfig& navigator() const { return navigator_; }
  [[nodiscard]] nav::mapmaker::CostCriterion criterion() const { return criterion_; }
  /// The least forecast reliability of a route the system will attempt (0: any).
  void refuse_below(double min_reliability) { min_reliability_ = min_reliability; }

 private:
  nav::mapmaker::MapMaker maker_;
  nav::mapmaker::CostCriterion criterion_;
  nav::navigator::NavigatorConfig navigator_;
  nav::navigator::Observer* observer_;
  double min_reliability_ = 0;
};

/// The route of a plan made by a ParkKenderSystem. Throws std::invalid_argument for another plan.
const nav::mapmaker::Route& route_of(const Plan& plan);

/// The navigator's own report of a journey run by a ParkKenderSystem, or null.
const nav::navigator::JourneyReport* navigator_report(const Travel& travel);

}  // namespace neopipe::rig
