#pragma once
// Internal to the navigator library: the state of one journey (the eye, the arm, what was seen
// last, the report being written) and the custom-map steps built on it. Everything here works in
// window coordinates (mm from the window's south-west corner); moving the tool by d moves the window
// by d, so an object seen at p is expected at p - d after the move.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "nav/common/custom_map.hpp"
#include "nav/navigator/navigator.hpp"

namespace neopipe::nav::navigator::detail {

class Pilot {
 public:
  Pilot(Eye& eye, Arm& arm, const NavigatorConfig& config, Observer* observer, JourneyReport& report)
      : eye_(eye), arm_(arm), config_(config), observer_(observer), report_(report) {}

  const NavigatorConfig& config() const { return config_; }
  const WindowModel& window() const { return config_.window; }
  JourneyReport& report() { return report_; }

  /// Grabs and processes a frame; the sighting stays current until the next look.
  const Sighting& look();
  const Sighting& sighting() const { return sighting_; }
  /// Commands a move of the window by `d` (tool frame, no turn) and looks again.
  const Sighting& move_and_look(const Eigen::Vector2d& d);
  /// False when the arm refused the last move (beyond its reach): it stayed where it was.
  bool moved() const { return moved_; }

  /// The navigator's estimate of how far its window has turned (rad, counter-clockwise) since the
  /// journey began, when the map-maker's axes and the window's were the same. The arm turns a little
  /// by error on every move and the navigator has no compass, but objects seen before and after a
  /// move show the turn: the window's heading is dead-reckoned from them.
  double heading() const { return heading_; }

  /// The sum of the moves made so far (mm), each turned by the heading estimated when it was
  /// commanded, so in the axes the journey began with. The navigator returns to a landmark it held
  /// earlier by undoing the moves since (follow.cpp); the arm's errors over those moves, and its
  /// turns where nothing was in view to measure them, are what the search for it must allow.
  const Eigen::Vector2d& odometry() const { return odometry_; }

 private:
  Eye& eye_;
  Arm& arm_;
  const NavigatorConfig& config_;
  Observer* observer_;
  JourneyReport& report_;
  Sighting sighting_;
  double heading_ = 0;
  Eigen::Vector2d odometry_ = Eigen::Vector2d::Zero();
  bool moved_ = true;
};

/// A failure the navigator is aware of; follow() turns it into the report's ending and reason.
struct Failure {
  Ending ending = Ending::lost;
  std::string reason;
  /// The landmark taken is known not to be the one described (its QOC says so): its entry's next
  /// candidate may be. Otherwise nothing the entry describes was found where the map says, so the
  /// landmark held before it is in doubt.
  bool wrong_candidate = false;
};

/// A landmark held at a corner: where it is seen in the window (within the adjust tolerance of the
/// corner's position).
struct Hold {
  Eigen::Vector2d landmark;
  Corner corner = Corner::SW;
};

/// Everything the sighting shows, in view or cut by the border.
std::vector<Eigen::Vector2d> everything_seen(const Sighting& sighting);

/// Index into `points` of the point nearest `predicted`, if one lies within `gate` mm.
std::optional<std::size_t> nearest(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& predicted,
                                   double gate);

/// How far an object seen before a move of length `moved` may appear from its predicted place.
double tracking_gate(double moved);

/// The view the map-maker predicts for `hold`: the window placed with the landmark exactly at its
/// corner. The real window is off by the adjust's residual (up to its tolerance), so it is judged
/// from everything seen, border caps included: an object is in view when its place relative to the
/// exact window is strictly inside it. The exact window is also the map-maker's axis-aligned one:
/// `heading` (Pilot::heading) undoes the window's turn. Points are in real window coordinates.
struct HeldView {
  std::vector<Eigen::Vector2d> points;
  std::size_t reference = 0;  ///< the held landmark
  std::vector<double> depth;  ///< per point: how far inside the exact window, mm (to its nearest border)
  /// Objects just outside the exact window (within NavigatorConfig::view_margin): the map-maker,
  /// placing objects with its own errors, may have counted them in view.
  std::vector<Eigen::Vector2d> just_outside;
  std::vector<double> outside_depth;  ///< per object just outside: how far inside (negative)
};
HeldView held_view(const Sighting& sighting, const Hold& hold, const WindowModel& window, double heading,
                   double margin = 0);

/// Visual servoing: brings the landmark now seen at `landmark` to `corner`. On success the landmark
/// is held there (within the adjust tolerance) and `landmark` is where it is seen; a Failure when it
/// is lost from sight or does not settle.
std::optional<Failure> adjust(Pilot& pilot, Eigen::Vector2d& landmark, Corner corner);

/// A landmark the navigator may take for a description, and whether it is in doubt: the view did
/// not show what the map-maker saw (an Obvious view with several objects, an object taken from just
/// outside the window), or it is not the first candidate.
struct SeekCandidate {
  Eigen::Vector2d landmark;
  bool doubtful = false;
};

/// The landmark `description` selects in the view of `hold`, with the map-maker's functions; with
/// `alternative` k > 0, the k-th next candidate. When the view has too few, the window looks beyond
/// its far edges (config.view_margin) for objects the map-maker placed inside. A Failure when there
/// is no such candidate.
std::optional<Failure> seek(Pilot& pilot, const Hold& hold, Description description, int alternative,
                            SeekCandidate& found);

/// Slides the window along the held landmark -> `via` (positive) or back, as `entry` says, until an
/// object that was not in view enters; `found` is where that new object is seen. With the entry's
/// SlideGoal, only an object entering where the goal should counts: one before it is passed by, one
/// after it ends the slide with a Failure (wrong_candidate: the goal went by beside the window). With `alternative` k >
/// 0 it goes on past the first k newcomers and takes the next. With an `offset` (mm, positive to the left of the
/// direction of travel) the window first moves that far across the track: a neighbouring placement,
/// for a goal that passed just beside the window. Failure after the map's bound, at most
/// config.max_slide.
std::optional<Failure> slide(Pilot& pilot, const Hold& hold, const Eigen::Vector2d& via, const MapEntry& entry,
                             int alternative, double offset, Eigen::Vector2d& found);

/// Looks around the landmark seen at `landmark` (holds it at each corner in turn) and counts the
/// occupied quadrants. Returns the hold it ends in (the last corner visited).
/// `qoc_low` and `qoc_high` bound the QOC the map-maker could have computed if objects within the
/// view margin of a border were on the other side of it.
struct Qoc {
  int measured = 0;
  int low = 0;
  int high = 0;
  /// Per quadrant (indexed by its Corner): an object clearly inside its window (deeper than the
  /// view margin), and anything in it or within the margin outside.
  std::array<bool, 4> clearly{};
  std::array<bool, 4> maybe{};
  /// What was seen, in the custom map's notation (unsure: only near a border).
  QuadrantPattern pattern() const;
  /// Whether the map's pattern could be this landmark's: no quadrant the map says is occupied is
  /// empty to the last margin, and none it says is empty holds an object clearly inside.
  bool agrees_with(const QuadrantPattern& map) const;
};
std::optional<Failure> measure_qoc(Pilot& pilot, Hold& hold, Qoc& qoc);

/// Verification and recovery of one entry (park-kender.md §7): measures the landmark's QOC and
/// follows the entry's rules until the QOC is the verified one. `landmark` becomes the object
/// finally taken; `record` gets the QOC and the recoveries.
/// `doubtful`: the landmark was a guess (SeekCandidate::doubtful), so an entry whose QOC is to be
/// measured only in doubt is measured.
std::optional<Failure> verify(Pilot& pilot, const MapEntry& entry, bool doubtful, Eigen::Vector2d& landmark,
                              EntryRecord& record);

}  // namespace neopipe::nav::navigator::detail
