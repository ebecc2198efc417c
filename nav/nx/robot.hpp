#pragma once
// NX's body in the dots world (qualnav.md §9): what it senses through the range ring and the
// compass, and how it moves (relative moves of the arm's tool, never a turn: the robot is a point,
// and headings come from the compass). Everything here is relative: NX never knows where it is.
//
// Gradients. A range r_i to marble i changes as −u_i · d when the robot moves by d (u_i the unit
// vector toward the marble), so its gradient is a unit vector pointing away from the marble. NX
// measures it by finite differences: it looks at its position and at two probes h mm along the
// tool's x and y axes (out and back, 4 moves), each look the mean of `reads` frames. A range is
// followed from one look to the next in its own sector when that sector's value stays within
// tolerance, else in a neighbouring sector (a marble whose bearing crosses a sector edge).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nav/common/arm.hpp"
#include "nav/common/compass.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::nav::nx {

inline constexpr int kSectors = 16;
inline constexpr double kSectorDeg = 22.5;

struct NxConfig {
  double probe_mm = 1.0;             ///< h of the finite differences
  int reads = 1;                     ///< frames averaged per look (more under range noise)
  double range_error = 0;            ///< the sensor's stated bound of relative error (its datasheet)
  int compass_reads = 16;            ///< readings averaged when NX re-reads its heading at a place
  double place_tolerance_mm = 0.05;  ///< hill-climbing stops when its step and spread are below this
  int max_climb_steps = 25;
  double max_climb_step_mm = 8;
  double step_mm = 4;                 ///< edge following: advance per step
  double arrival_gap_mm = 10;         ///< edge following: hill-climb once the third range is this close
  double max_edge_mm = 400;           ///< edge following: a longer edge is a dead end (open world)
  double clearance_mm = 11;           ///< never closer than this to a marble's surface (>= 10 mm, §2)
  double match_tolerance = 0.10;      ///< place matching: ranges agree within this fraction
  double heading_tolerance_deg = 15;  ///< place matching and slots: edge headings agree within this
  /// Place matching by dead reckoning: a place is where the odometry says within this, plus
  /// odometry_drift_mm times the square root of the moves made since the odometry was last anchored
  /// at a known place (the arm repeats each move only to about 0.05 mm, whatever its length).
  double position_tolerance_mm = 3;
  double odometry_drift_mm = 0.25;
  /// A known edge is avoided after this many failures (under range error one failure may be chance).
  int failures_to_avoid = 2;
};

/// One look: the 16 sectors' ranges (0: nothing in range).
using Scan = std::array<double, kSectors>;

/// A nearby marble as NX measures it at one point: its range and the range's unit gradient in the
/// tool frame (pointing away from the marble).
struct Neighbour {
  double range = 0;
  Eigen::Vector2d away = Eigen::Vector2d::Zero();
  int sector = 0;
};

/// The robot of one run: the ring (a frame source of 1 x 16 CV_32FC1 frames), the compass, the arm.
class Robot {
 public:
  Robot(pipeline::io::FrameSource& ring, nav::Compass& compass, nav::Arm& arm, const NxConfig& config);

  /// The mean of `reads` frames (0 if `reads` is 0: config.reads). Throws std::runtime_error for a
  /// frame that is not 1 x 16 CV_32FC1 or a source that ends.
  Scan look(int reads = 0);
  /// Moves by `d` mm in the tool frame; false when the arm refused.
  bool move(const Eigen::Vector2d& d);
  /// The `count` nearest marbles in view with their gradients, nearest first (fewer when fewer are
  /// in view or a gradient cannot be followed). `reads` as for look().
  std::vector<Neighbour> neighbours(int count, int reads = 0);
  /// Re-reads the compass (config.compass_reads readings averaged on the circle): the tool's heading.
  double read_heading();
  /// The heading last read, degrees counter-clockwise from the world's +x axis.
  [[nodiscard]] double heading() const { return heading_deg_; }
  /// A compass heading as a unit vector in the tool frame, and back.
  [[nodiscard]] Eigen::Vector2d tool_direction(double compass_deg) const;
  [[nodiscard]] double compass_heading(const Eigen::Vector2d& tool_direction) const;
  /// A vector of the tool frame in the compass frame (x: compass 0°).
  [[nodiscard]] Eigen::Vector2d compass_vector(const Eigen::Vector2d& tool_vector) const;

  /// Dead reckoning: every move the arm made, turned into the compass frame by the heading last read
  /// (the tool never turns on purpose, so its heading drifts only by the arm's rotation error). NX
  /// anchors it to a place's stored position whenever it knows where it is, so it drifts only over
  /// the moves since (each repeated by the arm to about 0.05 mm: position_radius).
  [[nodiscard]] const Eigen::Vector2d& odometry() const { return odometry_; }
  void set_odometry(const Eigen::Vector2d& position) {
    odometry_ = position;
    odometry_moves_ = 0;
  }

  /// The look at the robot's position that the last neighbours() started with.
  [[nodiscard]] const Scan& last_scan() const { return last_scan_; }
  [[nodiscard]] const NxConfig& config() const { return config_; }
  /// How far from the odometry a known place may lie and still be where NX stands.
  [[nodiscard]] double position_radius() const {
    return config_.position_tolerance_mm + config_.odometry_drift_mm * std::sqrt(static_cast<double>(odometry_moves_));
  }
  [[nodiscard]] std::int64_t frames() const { return frames_; }
  [[nodiscard]] std::int64_t moves() const { return moves_; }
  [[nodiscard]] std::int64_t refused_moves() const { return refused_; }
  [[nodiscard]] double travelled_mm() const { return travelled_; }

 private:
  pipeline::io::FrameSource& ring_;
  nav::Compass& compass_;
  nav::Arm& arm_;
  NxConfig config_;
  double heading_deg_ = 0;
  Eigen::Vector2d odometry_ = Eigen::Vector2d::Zero();
  std::int64_t odometry_moves_ = 0;
  Scan last_scan_{};
  std::int64_t frames_ = 0;
  std::int64_t moves_ = 0;
  std::int64_t refused_ = 0;
  double travelled_ = 0;
};

/// Degrees wrapped to (−180, 180].
double wrap180(double deg);

}  // namespace neopipe::nav::nx
