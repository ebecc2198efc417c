#include "rig/station.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

#include "rig/seeds.hpp"
#include "sim/arm/angles.hpp"
#include "sim/arm/scara_sizing.hpp"
#include "sim/camera_source.hpp"

namespace neopipe::rig {

using Eigen::Vector2d;

sim::MotionErrors motion_errors(const ArmErrors& e) {
  if (e.sigma_move == 0 && e.sigma_rot == 0) return sim::MotionErrors::none();
  sim::MotionErrors m;
  m.along_per_mm = e.sigma_move;
  m.across_per_mm = e.sigma_move;
  m.rotation_per_mm = sim::radians(e.sigma_rot);
  return m;
}

sim::ScaraGeometry arm_for_world(const sim::World& world, double window_side) {
  sim::ScaraGeometry g = sim::scara_for_workspace(world.size + Vector2d(2 * window_side, 2 * window_side));
  g.base -= Vector2d(window_side, window_side);
  return g;
}

// The navigators' only way to move: relative commands, which the simulated arm executes with its
// errors. A command the arm cannot reach leaves it where it was (as a real arm stopping at its
// limit would), so the navigator finds out by looking, not by an exception.
class Station::ArmAdapter final : public nav::Arm {
 public:
  ArmAdapter(sim::SimulatedArm& arm, ArmLog& log) : arm_(arm), log_(log) {}

  bool move_relative(double dx, double dy, double dtheta) override {
    ++log_.moves;
    log_.commanded_travel += std::hypot(dx, dy);
    const sim::Pose2 before = arm_.pose();
    try {
      arm_.move_relative(dx, dy, dtheta);
    } catch (const sim::ReachError&) {
      ++log_.refused_moves;
      return false;
    }
    const sim::Pose2& after = arm_.pose();
    log_.true_travel += std::hypot(after.x - before.x, after.y - before.y);
    log_.track.emplace_back(after.x, after.y);
    return true;
  }

 private:
  sim::SimulatedArm& arm_;
  ArmLog& log_;
};

// The compass reads the heading where the arm really is, with the sensor's error (the panoramic
// sensor's or the range ring's: `reading` reads it at a pose).
class Station::CompassAdapter final : public nav::Compass {
 public:
  CompassAdapter(std::function<double(const sim::Pose2&)> reading, double sigma_deg, const sim::SimulatedArm& arm)
      : reading_(std::move(reading)), sigma_deg_(sigma_deg), arm_(arm) {}
  nav::CompassReading read() override { return {reading_(arm_.pose()), sigma_deg_}; }

 private:
  std::function<double(const sim::Pose2&)> reading_;
  double sigma_deg_;
  const sim::SimulatedArm& arm_;
};

Station::Station(const sim::World& world, const StationSettings& settings, const sim::Pose2& start)
    : world_(world),
      settings_(settings),
      arm_(arm_for_world(world, settings.camera.window_mm), settings.motion, stream_seed(settings.seed, streams::arm),
           start),
      adapter_(std::make_unique<ArmAdapter>(arm_, log_)) {
  log_.track.emplace_back(start.x, start.y);
  if (settings.panorama) {
    sim::PanoramaSettings panorama = *settings.panorama;
    panorama.seed = stream_seed(settings.seed, streams::panorama);
    panorama_ = std::make_unique<sim::PanoramicSensor>(world_, panorama);
    compass_ = std::make_unique<CompassAdapter>([this](const sim::Pose2& p) { return panorama_->compass_deg(p); },
                                                panorama.compass_sigma_deg, arm_);
    camera_ = sim::panoramic_camera_source(*panorama_, [this] { return arm_.pose(); });
    return;
  }
  if (settings.range_ring) {
    sim::RangeRingSettings ring = *settings.range_ring;
    ring.seed = stream_seed(settings.seed, streams::range_ring);
    range_ring_ = std::make_unique<sim::RangeRingSensor>(world_, ring);
    compass_ = std::make_unique<CompassAdapter>([this](const sim::Pose2& p) { return range_ring_->compass_deg(p); },
                                                ring.compass_sigma_deg, arm_);
    camera_ = sim::range_ring_camera_source(*range_ring_, [this] { return arm_.pose(); });
    return;
  }
  sim::Rendering rendering = sim::rendering_for(settings.realism, sim::CameraKind::onboard, world.size);
  rendering.sensor.seed = stream_seed(settings.seed, streams::onboard_camera);
  const sim::OnboardCameraConfig camera = sim::onboard_config_for(rendering, world.marble_diameter, settings.camera);
  camera_ = sim::onboard_camera_source(
      world_, camera, rendering, [this] { return arm_.pose(); }, pipeline::io::ColorFormat::gray);
}

Station::~Station() = default;

nav::Arm& Station::arm() {
  return *adapter_;
}

pipeline::io::FrameSource& Station::camera() {
  return *camera_;
}

pipeline::io::FrameSource& Station::onboard_camera() {
  if (panorama_) throw std::logic_error("this station carries the panoramic sensor, not the onboard camera");
  if (range_ring_) throw std::logic_error("this station carries the range ring, not the onboard camera");
  return *camera_;
}

nav::Compass* Station::compass() {
  return compass_.get();
}

bool Station::tool_keeps_clear() const {
  const sim::Pose2& p = arm_.pose();
  return sim::keeps_clear(world_, {p.x, p.y});
}

const sim::Pose2& Station::tool() const {
  return arm_.pose();
}

Vector2d Station::to_world(const Vector2d& offset) const {
  const sim::Pose2& p = arm_.pose();
  const double c = std::cos(p.theta);
  const double s = std::sin(p.theta);
  return {p.x + c * offset.x() - s * offset.y(), p.y + s * offset.x() + c * offset.y()};
}

Vector2d Station::to_tool(const Vector2d& world) const {
  const sim::Pose2& p = arm_.pose();
  const Vector2d q = world - Vector2d(p.x, p.y);
  const double c = std::cos(p.theta);
  const double s = std::sin(p.theta);
  return {c * q.x() + s * q.y(), -s * q.x() + c * q.y()};
}

NearestObject Station::nearest_object(const Vector2d& world) const {
  NearestObject best{0, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < world_.objects.size(); ++i) {
    const double d = (world_.objects[i] - world).norm();
    if (d < best.distance) best = {static_cast<std::uint32_t>(i), d};
  }
  return best;
}

void Station::place_tool(const sim::Pose2& pose) {
  arm_.move_to(pose);
}

}  // namespace neopipe::rig
