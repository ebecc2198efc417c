#pragma once
// How a navigation system plugs into the rig. A system plans on the survey (what its map-maker may
// know), then travels with what the rig hands it: a camera (a frame source) and an arm (relative
// moves in the tool frame). It reports, as it goes, which landmark of its plan it believes it holds;
// the rig checks every such claim against the ground truth and assigns the outcome. Nothing in these
// interfaces carries the truth into a system, so Park & Kender's navigator, the qualitative
// relational map and Qualnav can all be judged on the same worlds, pairs and outcomes.

#include <Eigen/Core>
#include <any>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/common/compass.hpp"
#include "pipeline/io/frame_source.hpp"
#include "rig/outcome.hpp"

namespace neopipe::rig {

/// The planner found no way from the start to the goal.
class UnreachableGoal : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Which sensor a system travels with.
enum class Sensor {
  onboard_camera,  ///< looking down at a window beneath the tool (Park & Kender); gray8 frames
  panoramic,       ///< the 360° ring of marble identities and a compass (qualnav.md §2); s16 frames
  range_ring,      ///< NX's 16 range sensors and a compass (qualnav.md §9); 1 x 16 float frames
};

/// The camera a system travels with: the onboard camera, or the panoramic sensor, whose ring images
/// the engine's panorama graph reads (nav/common/panorama_reading.hpp).
struct CameraRequest {
  int side_px = 256;      ///< onboard: square image
  double window_mm = 50;  ///< onboard: side of the view window it shows
  Sensor sensor = Sensor::onboard_camera;
  double bearing_noise_deg = 0;  ///< panoramic: sd of the Gaussian jitter of each disc's bearing
  double range_error = 0.10;     ///< range ring: bound of each range's uniform relative error (0: off)
};

/// A journey as its system planned it: what the rig needs to place the arm and to judge. A system
/// derives its own plan type to carry its directions (a custom map, a landmark sequence, ...).
struct Plan {
  Plan() = default;
  Plan(const Plan&) = default;
  Plan& operator=(const Plan&) = default;
  virtual ~Plan() = default;

  std::uint32_t start = 0;
  std::uint32_t goal = 0;
  /// The landmark each entry of the directions means to hold; entry 0 is the start, where the rig
  /// places the arm. The last is the goal.
  std::vector<std::uint32_t> landmarks;
  /// Where the tool starts, from the start object's (true) position, mm, heading 0.
  Eigen::Vector2d start_offset = Eigen::Vector2d::Zero();
  double planned_reliability = 1;  ///< the planner's forecast that the journey reaches its goal
  double planned_distance = 0;     ///< mm the planner expects the tool to travel
  /// Non-empty: the system will not attempt this journey, and why (no route it can describe is as
  /// reliable as asked). The rig counts such plans as refusals, apart from failures.
  std::string refused;
};

/// Told by a system as it travels. The rig reads the truth at the moment of each call.
class Witness {
 public:
  virtual ~Witness() = default;
  /// The system believes it holds the landmark of entry `entry` of its plan, seen at `offset` mm from
  /// the tool in the tool frame (x along the tool's x axis, y along its y axis). A later claim of
  /// the same entry (after a recovery) replaces the earlier one.
  virtual void landmark_claimed(std::size_t entry, const Eigen::Vector2d& offset) = 0;

 protected:
  Witness() = default;
  Witness(const Witness&) = default;
  Witness& operator=(const Witness&) = default;
};

/// What a system hands the rig at the end of a journey.
struct Travel {
  Ending ending = Ending::arrived;
  std::string reason;       ///< for an aware failure: what could not be done, in the system's words
  int recoveries = 0;       ///< error recoveries it applied, of every kind
  int backtracks = 0;       ///< of which: returns to an earlier landmark to try another choice
  std::int64_t frames = 0;  ///< camera frames it processed
  std::any details;         ///< the system's own report (Park & Kender: nav::navigator::JourneyReport)
};

/// What a system travels with for one journey.
struct Equipment {
  pipeline::io::FrameSource& camera;
  nav::Arm& arm;
  /// The panoramic sensor's or the range ring's compass; null with the onboard camera. QRM must not
  /// read it.
  nav::Compass* compass = nullptr;
};

class NavigationSystem {
 public:
  virtual ~NavigationSystem() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  [[nodiscard]] virtual CameraRequest camera() const = 0;
  /// Plans a journey between two objects of the survey. Throws UnreachableGoal.
  [[nodiscard]] virtual std::unique_ptr<Plan> plan(std::uint32_t from, std::uint32_t to) const = 0;
  /// Follows `plan` (one this system made) from where the rig placed the arm. Never throws for a
  /// navigation failure: that ends the Travel. May be called from several threads at once, each
  /// with its own equipment and witness.
  virtual Travel travel(const Plan& plan, Equipment& equipment, Witness& witness) const = 0;

 protected:
  NavigationSystem() = default;
  NavigationSystem(const NavigationSystem&) = default;
  NavigationSystem& operator=(const NavigationSystem&) = default;
};

}  // namespace neopipe::rig
