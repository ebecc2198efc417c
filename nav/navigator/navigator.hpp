#pragma once
// The navigator (direction follower, park-kender.md §1, §7-9): follows a custom map with nothing
// but its onboard camera and relative arm moves. It sees the world only through a frame source and
// moves only through the Arm interface; it links neither the simulator nor the map-maker, so no
// ground truth can reach it (a link-time fact: see nav/navigator/CMakeLists.txt and its test).
//
// API contract shared by the navigator library (nav/navigator/) and the rig (rig/park_kender.*):
// change it only in both at once.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/common/custom_map.hpp"
#include "nav/common/window.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::nav::navigator {

/// The arm as the navigator commands it (nav/common/arm.hpp). The navigator never turns on purpose
/// (dtheta = 0); the real arm may, by error.
using Arm = nav::Arm;

/// What the navigator knows of its own camera: the square image shows exactly its view window, image
/// x along the tool's x axis, image up along its y axis, `side_px` pixels for `window.side` mm.
struct CameraModel {
  int side_px = 256;
  /// mm: the objects are identical marbles of this diameter. A marble cut by the image border shows
  /// only a cap whose centroid lies inside the window even when the marble's centre does not; the
  /// Eye puts such a marble's centre back where it is from the size of whole marbles' blobs (it
  /// measures that size; this is its first guess).
  double object_diameter = 5.0;
  /// px: blobs smaller than this are sensor noise, not marbles.
  int min_blob_area = 6;
  /// Gray levels a marble must stand above the image's median (the workspace) at its centroid. On a
  /// view with no marble Otsu's threshold splits the noise, and these blobs are not objects.
  int min_contrast = 30;
};

/// One look: blob centroids in window coordinates, mm, origin at the window's south-west corner,
/// x East (tool x), y North (tool y). Produced by the engine's blob graph on an onboard frame.
struct Sighting {
  std::int64_t frame = 0;
  std::vector<Eigen::Vector2d> objects;
  /// Marbles cut by the image border whose centres lie just outside the window (up to about a
  /// radius), centres estimated from the visible cap. Not in view; they let the navigator see what is
  /// about to enter while it slides, and judge views as if its landmark were exactly at its corner.
  std::vector<Eigen::Vector2d> partial;
};

struct NavigatorConfig {
  WindowModel window;  ///< side a and margin m, as the map-maker assumed
  CameraModel camera;
  double adjust_tolerance = 0.4;  ///< mm: a landmark this close to its corner position is held
  int max_adjust_moves = 8;       ///< servo iterations before the adjust counts as failed
  double slide_step = 2;          ///< mm per move while sliding (below a marble radius: slide.cpp)
  double max_slide = 2000;        ///< mm: a trajectory that meets nothing this far is lost
  /// Take a slide's goal only where the map says it enters (MapEntry::slide_goal), when it says.
  bool slide_goals = true;
  bool recovery = true;  ///< apply the map's recovery rules and backtrack (off: the "no recovery" runs)
  /// Candidates an entry may take after the description's choice, and returns to an earlier landmark
  /// a journey may make, when what follows a choice leads nowhere (follow.cpp). A slide's
  /// candidates are the slide beside the track on either side, slide_offset and then twice that
  /// away, then the track of the description's next landmark, then the next newcomers. Ten returns:
  /// a slide whose goal went by may take five before the right track (1.5 mm survey, 3 worlds x 5
  /// surveys x 200 journeys: 6 returns 95.4%, 10 returns 97.5%, 16 returns 97.6% with more unaware
  /// failures).
  int max_alternatives = 6;
  int max_backtracks = 10;
  /// What the navigator expects of its arm's unintended turns (sd per move: turn_sigma0 +
  /// turn_sigma_per_mm * length, rad) and of its own positions of whole marbles (sd, mm): it weighs
  /// the turn it measures from objects seen before and after each move by them.
  /// tracking (the default, an extension of the paper's navigator): the window's heading is
  /// dead-reckoned over the whole journey from marbles tracked across each move, and every view is
  /// judged with the window's turn undone. paper: no compass and no such memory, as the paper's
  /// navigator: views are judged in the window's own axes, whatever the arm turned by error.
  bool track_heading = true;
  double turn_sigma0 = 0.05 * std::numbers::pi / 180;         // rad
  double turn_sigma_per_mm = 0.002 * std::numbers::pi / 180;  // rad per mm moved
  double position_sigma = 0.015;                              // mm
  /// mm: objects this close to a window border, on either side, may have been in view or not for the
  /// map-maker (its positions have errors). When a view or a QOC measured as seen does not match the
  /// map, the navigator tries them on the other side before it gives up (seek.cpp, verify.cpp).
  double view_margin = 2.0;
  /// mm: how far beside the map's track a slide is tried again when its first newcomer led nowhere
  /// (the survey's errors turn the direction and move the goal: it may pass just beside the window).
  /// 0: no such retry, the next newcomer is the next candidate.
  double slide_offset = 0;
  /// Check the quadrants the map names for a verified QOC (QuadrantPattern), not only their count.
  bool quadrants = true;
};

/// How the journey ended, as the navigator knows it (the harness adds ground truth to make the six
/// outcomes of park-kender.md §9).
enum class Ending : std::uint8_t {
  arrived,        ///< followed every entry; believes it holds the goal
  lost,           ///< could not find what an entry describes (aware failure 1)
  unrecoverable,  ///< a verification failed and no rule applies (aware failure 2)
};

/// What happened at each entry, for the harness and the plots.
struct EntryRecord {
  std::size_t entry = 0;            ///< index into the custom map
  bool verified = false;            ///< QOC measured and equal to the map's (k, -)
  std::optional<int> measured_qoc;  ///< when it looked around
  int recoveries = 0;               ///< recovery rules applied at this entry
  int candidate = 0;                ///< which candidate the entry took (0: the description's choice)
  std::int64_t frames = 0;          ///< frames grabbed for this entry
};

struct JourneyReport {
  Ending ending = Ending::arrived;
  std::string reason;  ///< for lost / unrecoverable: what could not be done, in the map's words
  std::vector<EntryRecord> entries;
  int recoveries = 0;       ///< total recoveries: QOC rules applied plus backtracks
  int rule_recoveries = 0;  ///< the map's QOC recovery rules applied
  /// Returns to the landmark held before an entry to take its next candidate, after what followed
  /// it led nowhere (follow.cpp). An entry tried twice appears twice in `entries`.
  int backtracks = 0;
  std::int64_t frames = 0;      ///< onboard frames processed
  double commanded_travel = 0;  ///< mm, sum of |commanded moves|
};

/// Called by the navigator as it goes, so a harness can check each step against ground truth at the
/// moment it happens. Carries nothing into the navigator.
class Observer {
 public:
  virtual ~Observer() = default;
  /// The landmark of entry `entry` is now held at its corner (or identified, for the last entry),
  /// after any recovery. `window_position` is where the navigator sees it in its window.
  virtual void landmark_held(std::size_t /*entry*/, const Eigen::Vector2d& /*window_position*/) {}
  /// One frame was processed (for videos of the onboard view).
  virtual void frame_seen(const pipeline::io::SourceFrame& /*frame*/, const Sighting& /*sighting*/) {}
};

/// Runs the engine's blob graph (the same one `neopipe run` uses on marbles) on each frame of
/// `source` and maps the centroids to window coordinates.
class Eye {
 public:
  Eye(pipeline::io::FrameSource& source, const NavigatorConfig& config);
  ~Eye();
  Eye(const Eye&) = delete;
  Eye& operator=(const Eye&) = delete;
  /// Grabs and processes the next frame. Throws std::runtime_error when the source has ended.
  Sighting look();
  /// The frame behind the last sighting.
  const pipeline::io::SourceFrame& last_frame() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Follows `map` from its first entry, (*, c): the navigator starts holding the start object at c
/// (the harness placed it there). Never throws for navigation failures: they end the report.
JourneyReport follow(const CustomMap& map, Eye& eye, Arm& arm, const NavigatorConfig& config,
                     Observer* observer = nullptr);

}  // namespace neopipe::nav::navigator
