#pragma once
// QRM's navigator (spec qrm.md §8, §9): from the landmark nearest the robot, Dijkstra over the RNG
// estimated from its relational map, then head for the next landmark of the path in steps of δ
// along its bearing in the tool frame until it is the nearest landmark in view (the robot is in its
// Voronoi cell); drop it and re-plan, fusing a new image into the map every few steps. It sees the
// world only through an Eye (identified sightings: bearings in the tool frame and range estimates)
// and moves only through the Arm interface: no compass, no positions, no ground truth.
//
// Range estimates serve two things only: which landmark is nearest (the range order, as the map
// uses it) and the clearance rule, which keeps the tool sim::kMinClearanceMm from every marble's
// surface: a step whose end would come within the clearance of a marble's estimated position is
// not taken; another direction is (see navigate()).

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/common/panorama_reading.hpp"
#include "nav/qrm/observation.hpp"
#include "nav/qrm/relational_map.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::nav::qrm {

/// What the navigator looks through: one panorama's sightings at the tool's current pose.
class Eye {
 public:
  virtual ~Eye() = default;
  /// The sightings in view now, bearings in the tool frame. Empty when nothing is in view.
  virtual std::vector<PanoramaSighting> look() = 0;

 protected:
  Eye() = default;
  Eye(const Eye&) = default;
  Eye& operator=(const Eye&) = default;
};

/// The panoramic sensor's ring images through the engine's panorama graph.
class RingEye final : public Eye {
 public:
  /// `camera` must outlive the eye.
  RingEye(pipeline::io::FrameSource& camera, const PanoramaModel& model);
  /// Throws std::runtime_error when the camera gives no frame.
  std::vector<PanoramaSighting> look() override;

 private:
  pipeline::io::FrameSource& camera_;
  PanoramaReader reader_;
};

struct NavigatorConfig {
  double step_mm = 5;             ///< δ (spec §8)
  int fuse_every = 10;            ///< steps between two images fused into the map (spec §8)
  int max_steps = 1000;           ///< the step limit: 5 m at δ = 5 mm, several workspace diagonals
  double clearance_mm = 10;       ///< kept from every marble's surface (qualnav.md §2)
  double marble_radius_mm = 2.5;  ///< r_m: the clearance is from the centre + r_m
  /// Added to the clearance in the step rule: range estimates err by a few percent at close range.
  double clearance_margin_mm = 1.5;
  /// Looks in a row that may pass without the target in view (hidden behind a nearer marble) while
  /// the navigator walks on to where it last saw it; one more and the target is lost.
  int hidden_looks = 4;
  /// Steps round the nearest marble, per leg, looking for a next landmark not in view (an extension
  /// of spec §8, which fails at once: from beside a marble, its disc hides what lies behind it).
  int search_steps = 16;
  ObservationOptions observation;  ///< k = 18 nearest (spec §9)
  /// A sighting flagged partial (a disc partly hidden by a nearer one) has a range estimate too large
  /// by an unknown factor, which can invert the range order a measurement trusts: as the imaging
  /// tour does (rig/qrm_imaging.hpp), such sightings are left out of the images fused. They still
  /// count for the nearest landmark (never partial: the nearest disc is drawn over all) and clearance.
  bool fuse_partial_sightings = false;
};

/// How a journey ended, in the navigator's words.
enum class NavigationEnding : std::uint8_t {
  arrived,      ///< the goal is the nearest landmark in view
  no_path,      ///< the map's RNG estimate has no path from the nearest landmark to the goal
  target_lost,  ///< the next landmark of the path is not in view
  step_limit,   ///< max_steps taken without arriving
  blocked,      ///< no step of δ keeps the clearance, or the arm refused a move
};
inline constexpr std::size_t kNavigationEndings = 5;
std::string_view navigation_ending_name(NavigationEnding e);

/// Told each time the navigator holds a landmark of its path (it is the nearest in view).
class NavigationObserver {
 public:
  virtual ~NavigationObserver() = default;
  /// `offset`: where it sees the landmark, mm in the tool frame (bearing and range estimate).
  virtual void landmark_reached(LandmarkId id, const Eigen::Vector2d& offset) = 0;

 protected:
  NavigationObserver() = default;
  NavigationObserver(const NavigationObserver&) = default;
  NavigationObserver& operator=(const NavigationObserver&) = default;
};

struct NavigationReport {
  NavigationEnding ending = NavigationEnding::arrived;
  std::string reason;                   ///< for a failure, in words
  std::vector<LandmarkId> first_route;  ///< the first path planned, start first
  std::vector<LandmarkId> reached;      ///< landmarks held in order, the start first
  int steps = 0;                        ///< moves of δ commanded
  int detours = 0;                      ///< of which not along the target's bearing (clearance)
  int searches = 0;                     ///< of which round a marble, looking for a hidden target
  int replans = 0;                      ///< Dijkstra runs
  int reroutes = 0;                     ///< re-plans whose path left the previous one's remainder
  int images_fused = 0;
  std::int64_t frames = 0;       ///< images looked at
  std::size_t inconsistent = 0;  ///< measurements rolled back while fusing
};

/// Navigates to the landmark `goal` with `map` (the journey's copy, refined as it goes). `planned`:
/// the route planned before the journey, if any (on the map before this journey's images): a path
/// that leaves it counts as a re-route, as a later path that leaves the previous one does. Never
/// throws for a navigation failure; the report says how it ended.
NavigationReport navigate(RelationalMap& map, LandmarkId goal, Eye& eye, Arm& arm, const NavigatorConfig& config,
                          NavigationObserver* observer = nullptr, std::span<const LandmarkId> planned = {});

/// The sightings as the map takes them: bearing in radians, range estimate.
std::vector<LandmarkSighting> landmark_sightings(const std::vector<PanoramaSighting>& sightings);

}  // namespace neopipe::nav::qrm
