#pragma once
// The simulator dressed as the navigator's world, for tests: a SCARA arm with motion errors behind
// the navigator's Arm interface and its onboard camera as the Eye's frame source. The tests (not the
// navigator) read the ground truth through it.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include "nav/navigator/navigator.hpp"
#include "sim/arm/simulated_arm.hpp"
#include "sim/camera_source.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator::test_rig {

class SimArm final : public Arm {
 public:
  explicit SimArm(sim::SimulatedArm& arm) : arm_(arm) {}
  void move_relative(double dx, double dy, double dtheta) override {
    arm_.move_relative(dx, dy, dtheta);
    ++moves_;
  }
  int moves() const { return moves_; }

 private:
  sim::SimulatedArm& arm_;
  int moves_ = 0;
};

struct RigOptions {
  double window = 50;
  sim::MotionErrors errors;
  std::uint64_t seed = 1;
  sim::ImageModel image;
};

class Rig {
 public:
  Rig(sim::World world, const RigOptions& options = {})
      : world_(std::move(world)),
        options_(options),
        arm_(sim::ScaraGeometry{}, options.errors, options.seed, start_pose()),
        sim_arm_(arm_) {
    config_.window = WindowModel::with_side(options.window);
    sim::ImageModel image = options.image;
    image.seed = options.seed;
    camera_ = sim::onboard_camera_source(
        world_, sim::OnboardCameraConfig{config_.camera.side_px, options.window}, image, [this] { return arm_.pose(); },
        pipeline::io::ColorFormat::gray);
    eye_ = std::make_unique<Eye>(*camera_, config_);
  }
  // The camera follows this rig's arm (it captures `this`): a rig stays where it was made.
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  /// Places the tool exactly so that the window holds object `id` at `corner`: the window is
  /// centred on the tool, so the tool sits half a window North-East of the window's origin.
  void hold(std::size_t id, Corner corner) {
    const Eigen::Vector2d origin = config_.window.origin(world_.objects[id], corner);
    const double half = config_.window.side / 2;
    arm_.move_to({origin.x() + half, origin.y() + half, 0});
  }
  void place(const Eigen::Vector2d& window_origin) {
    const double half = config_.window.side / 2;
    arm_.move_to({window_origin.x() + half, window_origin.y() + half, 0});
  }

  /// World position of a point seen at window position `p`, from the tool's true pose.
  Eigen::Vector2d to_world(const Eigen::Vector2d& p) const {
    const sim::Pose2& pose = arm_.pose();
    const double half = config_.window.side / 2;
    const Eigen::Vector2d q = p - Eigen::Vector2d(half, half);
    const double c = std::cos(pose.theta);
    const double s = std::sin(pose.theta);
    return {pose.x + c * q.x() - s * q.y(), pose.y + s * q.x() + c * q.y()};
  }

  /// Where the world point `w` really is in the window, from the tool's true pose.
  Eigen::Vector2d to_window(const Eigen::Vector2d& w) const {
    const sim::Pose2& pose = arm_.pose();
    const double half = config_.window.side / 2;
    const Eigen::Vector2d q = w - Eigen::Vector2d(pose.x, pose.y);
    const double c = std::cos(pose.theta);
    const double s = std::sin(pose.theta);
    return Eigen::Vector2d(c * q.x() + s * q.y(), -s * q.x() + c * q.y()) + Eigen::Vector2d(half, half);
  }

  /// The object nearest the world point `w` and its distance.
  std::pair<std::size_t, double> nearest_object(const Eigen::Vector2d& w) const {
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < world_.objects.size(); ++i) {
      const double d = (world_.objects[i] - w).norm();
      if (d < best_d) {
        best = i;
        best_d = d;
      }
    }
    return {best, best_d};
  }

  const sim::World& world() const { return world_; }
  NavigatorConfig& config() { return config_; }
  Eye& eye() { return *eye_; }
  SimArm& arm() { return sim_arm_; }
  sim::SimulatedArm& sim_arm() { return arm_; }
  const sim::Pose2& pose() const { return arm_.pose(); }

 private:
  sim::Pose2 start_pose() const { return {world_.size.x() / 2, world_.size.y() / 2, 0}; }

  sim::World world_;
  RigOptions options_;
  sim::SimulatedArm arm_;
  SimArm sim_arm_;
  NavigatorConfig config_;
  std::unique_ptr<sim::SimCameraSource> camera_;
  std::unique_ptr<Eye> eye_;
};

/// Records where the navigator held each entry's landmark, in world coordinates (ground truth).
class TruthObserver final : public Observer {
 public:
  explicit TruthObserver(const Rig& rig) : rig_(rig) {}
  void landmark_held(std::size_t entry, const Eigen::Vector2d& window_position) override {
    held.emplace_back(entry, rig_.to_world(window_position));
  }
  void frame_seen(const pipeline::io::SourceFrame&, const Sighting&) override { ++frames; }

  std::vector<std::pair<std::size_t, Eigen::Vector2d>> held;
  std::int64_t frames = 0;

 private:
  const Rig& rig_;
};

}  // namespace neopipe::nav::navigator::test_rig
