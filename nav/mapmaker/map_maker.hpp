#pragma once
// The map-maker (direction giver): from object positions to a custom map the navigator can follow.
// Builds every view, parkway step and trajectory of the world once; plans a path between two
// objects under a cost criterion; checks each step's verification and recovery; writes the map.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/mapmaker/planner.hpp"
#include "nav/mapmaker/reliability.hpp"
#include "nav/mapmaker/steps.hpp"
#include "nav/mapmaker/verification.hpp"
#include "nav/mapmaker/views.hpp"
#include "nav/mapmaker/workspace.hpp"

namespace neopipe::nav::mapmaker {

struct MapMakerOptions {
  WindowModel window;
  NavigatorErrors errors;
  /// mm: an object this close to a quadrant's border may lie on either side for the navigator (the
  /// survey's and the navigator's position errors). Verification and recovery rules then hold
  /// whichever side it falls (check_step). 0: the map-maker's positions are taken as exact.
  double border_tolerance = 0;
  /// Describe landmarks as Far and Near too (the objects in view farthest from and nearest to the
  /// reference) beside the paper's Obvious and Isol (docs/navigation.md, "Descriptions").
  bool extended_descriptions = true;
  /// Say where each slide's goal should enter (SlideGoal), so that the navigator passes by an object
  /// entering before it and knows the goal went by when one enters after it.
  bool slide_goals = true;
};

struct RouteStep {
  Step step;
  StepCheck check;
  MapEntry entry;
  double distance = 0;  ///< travel counted for this step: to the adjust corner, or until identified at the goal
};

struct Route {
  std::uint32_t start = 0;
  std::uint32_t goal = 0;
  Corner start_corner = Corner::SW;
  CostCriterion criterion = CostCriterion::distance;
  std::vector<RouteStep> steps;
  double distance = 0;           ///< D: window travel, mm
  double unreliability = 0;      ///< U = -log R
  double landmark_distance = 0;  ///< sum of |landmark - reference| over the steps
  /// The forecast that the journey reaches the goal: the product of the steps' forecasts (with
  /// what the navigator recovers from), where e^-U is the chance it needs no recovery.
  double forecast = 1;
  double ratio() const;  ///< D / R
  CustomMap custom_map;
};

/// The goal cannot be reached from the start by any parkway step or trajectory.
class UnreachableGoal : public MapError {
 public:
  using MapError::MapError;
};

class MapMaker {
 public:
  MapMaker(Workspace workspace, const MapMakerOptions& options);
  MapMaker(const MapMaker&) = delete;
  MapMaker& operator=(const MapMaker&) = delete;

  const Workspace& workspace() const { return workspace_; }
  const WorldViews& views() const { return views_; }
  const StepTable& steps() const { return steps_; }
  const MapMakerOptions& options() const { return options_; }

  /// The best route from `start` to `goal` (object ids). The navigator starts holding `start` at
  /// the corner the plan chooses (the map's first entry, (*, corner)). Throws MapError for unknown
  /// ids or start == goal, UnreachableGoal when no path exists.
  Route plan(std::uint32_t start, std::uint32_t goal, CostCriterion criterion) const;

 private:
  Workspace workspace_;
  MapMakerOptions options_;
  WorldViews views_;
  StepTable steps_;
};

/// A step's kind as the route table names it: TRAJP, TRAJN, OBVIOUS or ISOL; FAR and NEAR, and
/// TRAJP-FAR, TRAJN-NEAR and so on, for the extended descriptions.
std::string_view step_description(const Step& step);

/// The human table of a route, like the paper's Fig. 30: from, to, description, distance,
/// unreliability, cost, and the verification/recovery line of each step.
std::string route_table(const Route& route);

}  // namespace neopipe::nav::mapmaker
