#pragma once
// The simulated equipment of one journey: the SCARA arm with its motion errors behind the
// navigators' Arm interface, and the onboard camera rendering the world at the arm's true pose as a
// frame source. The truth (the tool's pose, the world's objects) is read here, by the rig and by
// tests, and never handed to a navigator: a navigator gets only arm() and onboard_camera().

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/common/compass.hpp"
#include "pipeline/io/frame_source.hpp"
#include "sim/arm/motion_model.hpp"
#include "sim/arm/scara.hpp"
#include "sim/arm/simulated_arm.hpp"
#include "sim/cameras.hpp"
#include "sim/panorama.hpp"
#include "sim/pose2.hpp"
#include "sim/range_ring.hpp"
#include "sim/realism.hpp"
#include "sim/rendering.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// The arm's motion errors as an experiment states them.
struct ArmErrors {
  double sigma_move = 0.003;  ///< sd of the translation (along and across) per mm moved
  double sigma_rot = 0.002;   ///< sd of the heading, degrees per mm moved
};

/// The simulator's motion errors for these settings. With both per-mm terms 0 the arm is exact (no
/// repeatability floor either), so that error-free runs can be asked for.
sim::MotionErrors motion_errors(const ArmErrors& errors);

/// A SCARA arm that can hold a window anywhere over the world and one window beyond its edges, so a
/// trajectory may slide off the world without hitting the arm's reach first.
sim::ScaraGeometry arm_for_world(const sim::World& world, double window_side);

struct StationSettings {
  sim::MotionErrors motion;                  ///< the arm's errors (motion_errors(ArmErrors) for an experiment's)
  sim::OnboardCameraConfig camera;           ///< image size and view window (its plane follows the rendering)
  sim::Realism realism = sim::Realism::rig;  ///< of the onboard camera (its noise seeded per journey)
  std::uint64_t seed = 1;                    ///< this journey's arm errors and camera noise (two streams)
  /// Set: the tool carries the panoramic sensor instead of the onboard camera (its seed is replaced
  /// by this journey's panorama stream of `seed`).
  std::optional<sim::PanoramaSettings> panorama;
  /// Set (and no panorama): the tool carries NX's range ring and compass (its seed is replaced by
  /// this journey's range-ring stream of `seed`).
  std::optional<sim::RangeRingSettings> range_ring;
};

/// What the arm did, as the truth has it.
struct ArmLog {
  int moves = 0;                       ///< commands received
  double commanded_travel = 0;         ///< mm, what was asked for
  double true_travel = 0;              ///< mm, what the tool really moved
  int refused_moves = 0;               ///< commands out of reach (the arm stayed where it was)
  std::vector<Eigen::Vector2d> track;  ///< the tool's true position after each move, start first
};

/// The world object nearest a point, and how far it is.
struct NearestObject {
  std::uint32_t id = 0;
  double distance = 0;
};

class Station {
 public:
  /// The station over `world` (which must outlive it), the tool placed exactly at `start`.
  Station(const sim::World& world, const StationSettings& settings, const sim::Pose2& start);
  ~Station();
  // The camera follows this station's arm: a station stays where it was made.
  Station(const Station&) = delete;
  Station& operator=(const Station&) = delete;

  /// What a navigator gets.
  nav::Arm& arm();
  /// The camera the station carries: the onboard camera, the panoramic sensor's ring or the range ring.
  pipeline::io::FrameSource& camera();
  /// The same; throws std::logic_error if the station carries the panoramic sensor or the range ring.
  pipeline::io::FrameSource& onboard_camera();
  /// The panoramic sensor's or the range ring's compass, reading the tool's true heading with its
  /// error; null with the onboard camera.
  nav::Compass* compass();

  /// The truth.
  [[nodiscard]] const sim::Pose2& tool() const;
  /// World position of a point `offset` mm from the tool in the tool frame.
  [[nodiscard]] Eigen::Vector2d to_world(const Eigen::Vector2d& offset) const;
  /// Where the world point `world` is from the tool, in the tool frame.
  [[nodiscard]] Eigen::Vector2d to_tool(const Eigen::Vector2d& world) const;
  [[nodiscard]] NearestObject nearest_object(const Eigen::Vector2d& world) const;
  /// Whether the tool keeps sim::kMinClearanceMm from every marble's surface, as the robot carrying
  /// the panoramic sensor must (qualnav.md §2).
  [[nodiscard]] bool tool_keeps_clear() const;
  [[nodiscard]] const ArmLog& log() const { return log_; }
  [[nodiscard]] const sim::World& world() const { return world_; }
  [[nodiscard]] const StationSettings& settings() const { return settings_; }

  /// Puts the tool exactly at `pose`, as a set-up step (no error, not logged as travel).
  void place_tool(const sim::Pose2& pose);

 private:
  class ArmAdapter;
  class CompassAdapter;

  const sim::World& world_;
  StationSettings settings_;
  sim::SimulatedArm arm_;
  ArmLog log_;
  std::unique_ptr<ArmAdapter> adapter_;
  std::unique_ptr<sim::PanoramicSensor> panorama_;
  std::unique_ptr<sim::RangeRingSensor> range_ring_;
  std::unique_ptr<CompassAdapter> compass_;
  std::unique_ptr<pipeline::io::FrameSource> camera_;
};

}  // namespace neopipe::rig
