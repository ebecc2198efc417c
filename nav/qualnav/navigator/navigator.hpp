#pragma once
// Qualnav's navigator (qualnav.md §6, §7; seed 003 §3): from a visual memory to a goal landmark.
//
// Every step: look (a viewframe), plan by A* over the memory with the viewframe just taken as an
// extra node linked to every remembered viewframe it shares ≥ 2 landmarks with and whose viewframe
// heading is ≤ 150 mm (none: to the nearest by heading — rule (2)'s chain back), to the
// remembered viewframe nearest the goal landmark; take one step of the viewframe heading towards the
// plan's first node; re-plan. Shortcuts appear as links from the new viewframe to nodes further on,
// so the executed path is shorter and smoother than the remembered one.
//
// When the plan's next node is the goal viewframe and its heading is short, or the goal landmark's
// range interval lies within `approach_mm`, the goal's orientation heading a[P P] takes over
// (Decision: head for P, stop at 15 mm): steps along its bearing that cannot overshoot (by the range
// interval's lower end), then two parallax looks fix the range, the stop at 15 mm, and the offset
// it claims. Optionally (hill_climb) the last stretch to the goal viewframe descends the relative
// angles of its landmarks first.
//
// It sees the world only through a ViewSource and moves only through the Arm (relative moves, never
// turning): no positions, no ground truth.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/qualnav/metric/visual_memory.hpp"
#include "nav/qualnav/navigator/hill_climb.hpp"
#include "nav/qualnav/navigator/motion.hpp"
#include "nav/qualnav/navigator/view_source.hpp"

namespace neopipe::nav::qualnav {

struct NavigatorConfig {
  double step_mm = 10;      ///< one step of a viewframe heading (re-plan after each)
  int max_steps = 400;      ///< moves of every kind
  double stop_mm = 15;      ///< the a heading stops this far from the goal's centre (Decision)
  double approach_mm = 40;  ///< a heading once the goal's whole range interval is nearer than this
  double handover_mm = 12;  ///< ... or the heading to the goal viewframe is shorter than this
  double parallax_mm = 6;   ///< the sideways baseline of a range by parallax
  double link_mm = kLinkDistanceMm;
  ClearanceRule clearance;
  /// Looks from where it stands when no move keeps the clearance by the bounds so far.
  int extra_looks = 6;
  bool hill_climb = false;  ///< descend the goal viewframe's relative angles before the a heading
  /// Steer each step down the relative-angle error to the plan's next viewframe (the hill-climb's
  /// direction, range-free but for its scale) instead of along the viewframe heading, whose length
  /// still sets the step and the plan. The heading alone rests on the range intervals: at 50 %
  /// error its direction wanders from look to look.
  bool steer_by_angles = false;
  /// Viewframe headings averaged over this many frames (the widest pairs first): one frame rests on
  /// two landmarks' range intervals, several on more.
  int frames = 5;
  /// Each heading step's direction is this much the previous step's and the rest the new heading's
  /// (0: none). The headings' noise at large range errors otherwise zig-zags the path.
  double smoothing = 0.6;
  /// Localize the view with its range bounds fused over the looks so far (the clearance's) rather
  /// than the single look's intervals.
  bool fused_ranges = false;
  HillClimbSettings climb;
};

enum class NavigationEnding : std::uint8_t {
  arrived,     ///< stopped at the goal by the a heading, its range fixed by parallax
  no_memory,   ///< the memory holds no viewframe that sees the goal, or none the robot can relate to
  lost,        ///< no viewframe of the memory shares a localizable pair with the view (rule 3: fail)
  goal_lost,   ///< the goal landmark left the view during the a heading
  step_limit,  ///< max_steps moves without arriving
  blocked,     ///< no move keeps the clearance, or the arm refused one
};
inline constexpr std::size_t kNavigationEndings = 6;
std::string_view navigation_ending_name(NavigationEnding e);

/// Told when the navigator believes it holds the goal.
class GoalObserver {
 public:
  virtual ~GoalObserver() = default;
  /// `offset`: where it sees the goal, mm in the tool frame.
  virtual void goal_held(const Eigen::Vector2d& offset) = 0;

 protected:
  GoalObserver() = default;
  GoalObserver(const GoalObserver&) = default;
  GoalObserver& operator=(const GoalObserver&) = default;
};

/// What the orientation-region level (region_level.hpp) did before the viewframe level finished the
/// journey; all zero when the journey ran at the viewframe level only.
struct RegionLevelCounters {
  bool used = false;         ///< the journey started at the region level
  std::string ending;        ///< how the region phase ended (region_phase_ending_name)
  int plan_regions = 0;      ///< regions of the first region plan, start and goal included
  int regions_crossed = 0;   ///< planned regions the robot entered (a shortcut counts every region skipped)
  int shortcuts = 0;         ///< heads straight to a later planned region (the paper's shortcut)
  int production_steps = 0;  ///< steps steered by an orientation heading of the productions
  int fallback_steps = 0;    ///< steps by a viewframe heading where the production was "–" or undefined
  int fallbacks = 0;         ///< 1 when the region phase failed (lost, stalled, blocked): viewframe level
  int steps = 0;             ///< moves of the region phase
  double path_mm = 0;        ///< path moves of the region phase
};

struct NavigationReport {
  NavigationEnding ending = NavigationEnding::arrived;
  std::string reason;
  int steps = 0;                        ///< moves commanded (every kind)
  int heading_steps = 0;                ///< of which viewframe-heading steps
  int climb_steps = 0;                  ///< hill-climb steps
  int approach_steps = 0;               ///< a-heading steps, parallax moves included
  int detours = 0;                      ///< moves turned away from their heading for the clearance
  int replans = 0;                      ///< A* runs
  int shortcuts = 0;                    ///< plans whose next node skips remembered viewframes of the previous plan
  std::vector<std::size_t> first_plan;  ///< memory nodes of the first plan
  double commanded_mm = 0;              ///< the moves' total length
  /// The sum of the absolute turns between consecutive path moves (heading, hill-climb and a-heading
  /// steps; the parallax moves and the stop are left out), rad: how smooth the executed path is.
  double path_turning = 0;
  double path_mm = 0;        ///< the path moves' total length (to where the stop's parallax begins)
  double goal_range_mm = 0;  ///< the parallax range at the stop
  Eigen::Vector2d claimed_offset = Eigen::Vector2d::Zero();
  /// Where the path moves took the tool by dead reckoning, in the start's tool frame, start first.
  std::vector<Eigen::Vector2d> path;
  RegionLevelCounters regions;
};

/// The memory node nearest the goal landmark: the viewframe that sees it at the smallest range
/// estimate; nullopt when none sees it.
std::optional<std::size_t> goal_node(const VisualMemory& memory, LandmarkId goal);

/// Navigates to `goal`. Never throws for a navigation failure.
NavigationReport navigate(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm,
                          const NavigatorConfig& config, GoalObserver* observer = nullptr);

}  // namespace neopipe::nav::qualnav
