#pragma once
// Qualnav's orientation-region level (qualnav.md §1, §5, §6, §7; seed 002 Fig. 13): plan over the
// orientation regions of the remembered viewframes, execute by crossing the planned LPBs with the
// orientation headings their productions give, and hand the last stretch to the viewframe level.
//
// The regions are those of a few landmarks (Decision of this implementation, not of the papers: the
// goal and the landmarks the memory saw nearest, `RegionLevelConfig::landmarks` in all; the paper's
// arrangement has 7). With every landmark of a 30-marble world in view, 435 LPBs would cut the
// route into regions a few millimetres wide and every step would cross several.
//
// Each step: look; the robot is in a planned region when no LPB of that region that it can see has
// the other sign (an LPB out of view cannot be told), the LPBs the plan crosses into it all seen; it
// advances to the furthest such region of the plan. It heads for the furthest later region whose
// LPBs are all in view and whose separating LPBs have a production other than "–" (the paper's
// shortcut; the aim holds until reached or a further one opens), else for the next region, steering by the production's
// orientation heading (b along the bisector, l and r beside P or Q, a at P). Where the next region's production is "–"
// or undefined (no 180° gap among the separating landmarks), one step of the viewframe heading to a remembered
// viewframe of that region takes its place. In the goal's region, or with the goal's range interval within the approach
// distance, the viewframe level (navigator.hpp) finishes: viewframe headings to the goal's viewframe, then the goal's a
// heading and the parallax stop.
//
// Failures fall back a level (§1): `lost` (the view relates to no remembered region, or no
// viewframe heading to the target region), `stalled` (no region entered and the separating LPBs not
// fewer for `stall_steps` steps) and `blocked` (no step keeps the clearance) hand the journey to the
// viewframe level from where the robot stands.

#include <cstdint>
#include <string_view>

#include "nav/common/arm.hpp"
#include "nav/qualnav/metric/visual_memory.hpp"
#include "nav/qualnav/navigator/navigator.hpp"
#include "nav/qualnav/navigator/view_source.hpp"

namespace neopipe::nav::qualnav {

struct RegionLevelConfig {
  int landmarks = 7;     ///< the goal and the landmarks seen nearest along the memory
  int stall_steps = 10;  ///< steps without progress before the region phase is stalled
  /// Landmarks the memory passed nearer than this (the start's marble, the route's near-misses) are
  /// left out, the goal excepted: beside a marble a 10 mm step flips the sides of its LPBs back and
  /// forth, and the steering chased those flips.
  double min_range_mm = 30;
};

/// How the region phase ended.
enum class RegionPhaseEnding : std::uint8_t {
  goal_region,  ///< in the goal's region: the viewframe level finishes
  goal_near,    ///< the goal's range interval within the approach distance: the viewframe level finishes
  lost,         ///< fallback: no remembered region or viewframe heading relates to the view
  stalled,      ///< fallback: no progress for stall_steps steps
  blocked,      ///< fallback: no step keeps the clearance, or the arm refused one
  step_limit,   ///< the journey's step limit ran out in the region phase
};
std::string_view region_phase_ending_name(RegionPhaseEnding e);

/// The landmarks of the region level: `goal` and the others by the smallest range estimate any
/// remembered viewframe has of them, those under `min_range_mm` left out, `count` in all (fewer when
/// the memory sees fewer), ascending.
std::vector<LandmarkId> region_landmarks(const VisualMemory& memory, LandmarkId goal, int count,
                                         double min_range_mm = 0);

/// Navigates to `goal` starting at the region level. The report is the journey's whole (steps, path,
/// turning, the ending of the viewframe level that finished it) with `regions` filled in. Never throws
/// for a navigation failure.
NavigationReport navigate_regions(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm,
                                  const NavigatorConfig& config, const RegionLevelConfig& regions,
                                  GoalObserver* observer = nullptr);

}  // namespace neopipe::nav::qualnav
