#pragma once
// The rig's station (rig/station.hpp: the simulated arm behind the navigator's Arm interface, its
// onboard camera as the Eye's frame source) in the navigator's window coordinates, for tests that
// drive the navigator's steps one at a time. The tests (not the navigator) read the ground truth
// through it.

#include <Eigen/Core>
#include <memory>
#include <utility>

#include "nav/navigator/navigator.hpp"
#include "rig/station.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator::test_rig {

struct RigOptions {
  double window = 50;
  sim::MotionErrors errors;
  std::uint64_t seed = 1;
  sim::Realism realism = sim::Realism::rig;
};

class Rig {
 public:
  explicit Rig(sim::World world, const RigOptions& options = {})
      : world_(std::move(world)), station_(world_, station_settings(options), centre(world_)) {
    config_.window = WindowModel::with_side(options.window);
    eye_ = std::make_unique<Eye>(station_.onboard_camera(), config_);
  }
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  /// Places the tool exactly so that the window holds object `id` at `corner`: the window is
  /// centred on the tool, so the tool sits half a window North-East of the window's origin.
  void hold(std::size_t id, Corner corner) { place(config_.window.origin(world_.objects[id], corner)); }
  void place(const Eigen::Vector2d& window_origin) {
    const Eigen::Vector2d tool = window_origin + half();
    station_.place_tool({tool.x(), tool.y(), 0});
  }

  /// World position of a point seen at window position `p`, from the tool's true pose.
  Eigen::Vector2d to_world(const Eigen::Vector2d& p) const { return station_.to_world(p - half()); }
  /// Where the world point `w` really is in the window, from the tool's true pose.
  Eigen::Vector2d to_window(const Eigen::Vector2d& w) const { return station_.to_tool(w) + half(); }
  /// The object nearest the world point `w` and its distance.
  std::pair<std::size_t, double> nearest_object(const Eigen::Vector2d& w) const {
    const rig::NearestObject n = station_.nearest_object(w);
    return {n.id, n.distance};
  }

  const sim::World& world() const { return world_; }
  NavigatorConfig& config() { return config_; }
  Eye& eye() { return *eye_; }
  Arm& arm() { return station_.arm(); }
  /// Commands the arm has received.
  int moves() const { return station_.log().moves; }
  const sim::Pose2& pose() const { return station_.tool(); }

 private:
  static rig::StationSettings station_settings(const RigOptions& o) {
    rig::StationSettings s;
    s.motion = o.errors;
    s.camera.side_px = NavigatorConfig{}.camera.side_px;
    s.camera.window_mm = o.window;
    s.realism = o.realism;
    s.seed = o.seed;
    return s;
  }
  static sim::Pose2 centre(const sim::World& w) { return {w.size.x() / 2, w.size.y() / 2, 0}; }
  Eigen::Vector2d half() const { return Eigen::Vector2d::Constant(config_.window.side / 2); }

  sim::World world_;  // before the station, which keeps a reference to it
  rig::Station station_;
  NavigatorConfig config_;
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
