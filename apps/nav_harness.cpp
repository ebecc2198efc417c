#include "apps/nav_harness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/arm/angles.hpp"
#include "sim/arm/scara_sizing.hpp"
#include "sim/arm/simulated_arm.hpp"
#include "sim/camera_source.hpp"
#include "sim/random.hpp"

namespace neopipe::apps {
namespace {

using Eigen::Vector2d;
namespace nv = nav::navigator;

// The navigator's only way to move: relative commands, which the simulated arm executes with its
// errors. A command the arm cannot reach leaves it where it was (as a real arm stopping at its
// limit would), so the navigator finds out by looking, not by an exception.
class SimArmAdapter final : public nv::Arm {
 public:
  SimArmAdapter(sim::SimulatedArm& arm, JourneyResult& result) : arm_(arm), result_(result) {
    result_.track.emplace_back(arm_.pose().x, arm_.pose().y);
  }

  void move_relative(double dx, double dy, double dtheta) override {
    result_.commanded_travel += std::hypot(dx, dy);
    const sim::Pose2 before = arm_.pose();
    try {
      arm_.move_relative(dx, dy, dtheta);
    } catch (const sim::ReachError&) {
      ++result_.refused_moves;
      return;
    }
    const sim::Pose2& after = arm_.pose();
    result_.true_travel += std::hypot(after.x - before.x, after.y - before.y);
    result_.track.emplace_back(after.x, after.y);
  }

 private:
  sim::SimulatedArm& arm_;
  JourneyResult& result_;
};

// Looks over the navigator's shoulder with the ground truth: which world object it really holds
// when it says it holds an entry's landmark.
class TruthObserver final : public nv::Observer {
 public:
  TruthObserver(const sim::World& world, const nav::mapmaker::Route& route, const sim::SimulatedArm& arm,
                double window_side, JourneyResult& result, nv::Observer* next)
      : world_(world), route_(route), arm_(arm), side_(window_side), result_(result), next_(next) {}

  void landmark_held(std::size_t entry, const Vector2d& window_position) override {
    const sim::Pose2& pose = arm_.pose();
    const Vector2d tool(pose.x, pose.y);
    const Vector2d local = window_position - Vector2d(side_ / 2, side_ / 2);
    const double c = std::cos(pose.theta);
    const double s = std::sin(pose.theta);
    const Vector2d at = tool + Vector2d(c * local.x() - s * local.y(), s * local.x() + c * local.y());
    HeldLandmark h;
    h.entry = entry;
    h.tool = tool;
    h.intended = entry == 0                        ? route_.start
                 : entry - 1 < route_.steps.size() ? route_.steps[entry - 1].step.landmark
                                                   : std::numeric_limits<std::uint32_t>::max();
    h.offset = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < world_.objects.size(); ++i) {
      const double d = (world_.objects[i] - at).norm();
      if (d < h.offset) {
        h.offset = d;
        h.actual = static_cast<std::uint32_t>(i);
      }
    }
    // Holding empty space near an object is not holding it: beyond a marble's diameter the
    // navigator is looking at something the map-maker never meant.
    h.correct = h.actual == h.intended && h.offset <= world_.marble_diameter;
    result_.held.push_back(h);
    if (next_ != nullptr) next_->landmark_held(entry, window_position);
  }

  void frame_seen(const pipeline::io::SourceFrame& frame, const nv::Sighting& sighting) override {
    if (next_ != nullptr) next_->frame_seen(frame, sighting);
  }

 private:
  const sim::World& world_;
  const nav::mapmaker::Route& route_;
  const sim::SimulatedArm& arm_;
  double side_;
  JourneyResult& result_;
  nv::Observer* next_;
};

// The truth of the journey from the held landmarks: the last word on each entry counts (a recovery
// may hold an entry again). Entry 0 is the start, placed by the harness; only the steps must be
// reported.
JourneyTruth judge(const JourneyResult& r, const nav::mapmaker::Route& route) {
  JourneyTruth t;
  t.ending = r.report.ending;
  t.recoveries = r.report.recoveries;
  const std::size_t entries = route.steps.size() + 1;
  std::vector<const HeldLandmark*> last(entries, nullptr);
  for (const HeldLandmark& h : r.held) {
    if (h.entry < entries) last[h.entry] = &h;
  }
  t.every_step_correct = true;
  for (std::size_t e = 0; e < entries; ++e) {
    if ((e > 0 && last[e] == nullptr) || (last[e] != nullptr && !last[e]->correct)) t.every_step_correct = false;
  }
  t.goal_held = last.back() != nullptr && last.back()->actual == route.goal && last.back()->correct;
  return t;
}

}  // namespace

sim::MotionErrors motion_errors(const ExperimentErrors& e) {
  if (e.sigma_move == 0 && e.sigma_rot == 0) return sim::MotionErrors::none();
  sim::MotionErrors m;
  m.along_per_mm = e.sigma_move;
  m.across_per_mm = e.sigma_move;
  m.rotation_per_mm = sim::radians(e.sigma_rot);
  return m;
}

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream) {
  sim::Random r(seed ^ (0x9E3779B97F4A7C15ULL * (stream + 1)));
  return r.next();
}

sim::ScaraGeometry arm_for_world(const sim::World& world, double window_side) {
  sim::ScaraGeometry g = sim::scara_for_workspace(world.size + Vector2d(2 * window_side, 2 * window_side));
  g.base -= Vector2d(window_side, window_side);
  return g;
}

JourneyResult run_journey(const sim::World& world, const nav::mapmaker::Route& route, const JourneySettings& settings,
                          nv::Observer* observer) {
  JourneyResult result;
  const nav::WindowModel& window = settings.navigator.window;
  const Vector2d tool =
      window.origin(world.objects.at(route.start), route.start_corner) + Vector2d(window.side / 2, window.side / 2);
  sim::SimulatedArm arm(arm_for_world(world, window.side), motion_errors(settings.errors),
                        stream_seed(settings.seed, 0), sim::Pose2{tool.x(), tool.y(), 0});
  sim::OnboardCameraConfig camera;
  camera.side_px = settings.navigator.camera.side_px;
  camera.window_mm = window.side;
  sim::ImageModel image;
  image.seed = stream_seed(settings.seed, 1);
  const auto source = sim::onboard_camera_source(
      world, camera, image, [&arm] { return arm.pose(); }, pipeline::io::ColorFormat::gray);
  nv::Eye eye(*source, settings.navigator);
  SimArmAdapter adapter(arm, result);
  TruthObserver truth(world, route, arm, window.side, result, observer);
  result.report = nv::follow(route.custom_map, eye, adapter, settings.navigator, &truth);
  result.frames = result.report.frames;
  result.outcome = classify(judge(result, route));
  return result;
}

}  // namespace neopipe::apps
