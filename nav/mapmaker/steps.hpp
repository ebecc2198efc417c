#pragma once
// The steps of the context-based graph (park-kender.md §5.4): from a placement (R, c) the navigator
// can seek the landmark its view describes (a parkway step) or slide along a trajectory, then
// adjust what it found to any corner M. A step's cost is the window's real travel, its reliability
// the product of its selection and trajectory reliabilities.

#include <cstdint>
#include <optional>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/mapmaker/reliability.hpp"
#include "nav/mapmaker/trajectories.hpp"
#include "nav/mapmaker/views.hpp"

namespace neopipe::nav::mapmaker {

struct Step {
  Placement from;
  std::uint32_t landmark = 0;            ///< the object reached
  Corner adjust = Corner::SW;            ///< M: where the landmark is held afterwards
  Description seek = Description::Isol;  ///< D: how the (first) landmark is described
  std::optional<Direction> slide;        ///< T: a trajectory step
  std::uint32_t via = 0;                 ///< the described landmark (the landmark itself if no slide)
  double travel = 0;                     ///< window travel incl. the adjust to M, mm (the edge's D)
  double arrival_travel = 0;             ///< window travel until the landmark is identified (no adjust), mm
  double landmark_distance = 0;          ///< |landmark - reference|, the landmark-based distance
  int visible = 0;                       ///< objects in view at `from`, the reference included
  /// R of the step: that the navigator does what the map-maker predicts, first time. The planner
  /// minimises -log R: it seeks routes that need no recovery.
  double reliability = 1;
  /// The chance that the step costs the journey nothing, with what the navigator recovers from
  /// (RecoveryCredit): the forecast. Not planned on: a planner rewarded for recoverable risk takes
  /// the risks it cannot recover from (docs/navigation.md, "Recovery credit").
  double forecast = 1;

  double unreliability() const;  ///< -log R
};

/// Every step of a world, grouped by placement node (steps_from(node)), each group in preference
/// order: landmarks farther from the reference first (park-kender.md §5 tie rule), then parkway
/// before trajectory, Trajp before Trajn, corners SE, SW, NE, NW.
class StepTable {
 public:
  /// extended: also the steps whose landmark is described as Far or Near, where they name another
  /// object than the paper's description does (docs/navigation.md, "Descriptions").
  StepTable(const WorldViews& views, const NavigatorErrors& errors, bool extended = false);

  const std::vector<Step>& steps() const { return steps_; }
  /// Indices into steps() of the steps leaving `node`.
  std::pair<std::uint32_t, std::uint32_t> range(std::uint32_t node) const { return {first_[node], first_[node + 1]}; }
  const std::vector<Trajectory>& trajectories() const { return trajectories_; }

 private:
  std::vector<Step> steps_;
  std::vector<std::uint32_t> first_;
  std::vector<Trajectory> trajectories_;
};

}  // namespace neopipe::nav::mapmaker
