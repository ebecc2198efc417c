#include "rig/journey.hpp"

#include <limits>

namespace neopipe::rig {
namespace {

using Eigen::Vector2d;

// Checks each claim against the truth at the moment it is made: which world object is really at
// the position the system says it holds.
class TruthWitness final : public Witness {
 public:
  TruthWitness(const Station& station, const Plan& plan, std::vector<HeldLandmark>& held)
      : station_(station), plan_(plan), held_(held) {}

  void landmark_claimed(std::size_t entry, const Vector2d& offset) override {
    const sim::Pose2& pose = station_.tool();
    const Vector2d at = station_.to_world(offset);
    HeldLandmark h;
    h.entry = entry;
    h.tool = {pose.x, pose.y};
    h.intended = entry < plan_.landmarks.size() ? plan_.landmarks[entry] : std::numeric_limits<std::uint32_t>::max();
    const NearestObject nearest = station_.nearest_object(at);
    h.actual = nearest.id;
    h.offset = nearest.distance;
    // Holding empty space near an object is not holding it: beyond a marble's diameter the system
    // is looking at something its plan never meant.
    h.correct = h.actual == h.intended && h.offset <= station_.world().marble_diameter;
    held_.push_back(h);
  }

 private:
  const Station& station_;
  const Plan& plan_;
  std::vector<HeldLandmark>& held_;
};

}  // namespace

JourneyTruth judge(const std::vector<HeldLandmark>& held, const Plan& plan, const Travel& travel) {
  JourneyTruth t;
  t.ending = travel.ending;
  t.recoveries = travel.recoveries;
  const std::size_t entries = plan.landmarks.size();
  std::vector<const HeldLandmark*> last(entries, nullptr);
  for (const HeldLandmark& h : held) {
    if (h.entry < entries) last[h.entry] = &h;
  }
  t.every_step_correct = true;
  for (std::size_t e = 0; e < entries; ++e) {
    if ((e > 0 && last[e] == nullptr) || (last[e] != nullptr && !last[e]->correct)) t.every_step_correct = false;
  }
  t.goal_held = entries > 0 && last.back() != nullptr && last.back()->actual == plan.goal && last.back()->correct;
  return t;
}

JourneyResult run_journey(const NavigationSystem& system, const Plan& plan, const sim::World& world,
                          const JourneySettings& settings) {
  const CameraRequest request = system.camera();
  StationSettings station_settings;
  station_settings.motion = motion_errors(settings.errors);
  station_settings.camera.side_px = request.side_px;
  station_settings.camera.window_mm = request.window_mm;
  station_settings.realism = settings.realism;
  station_settings.seed = settings.seed;
  if (request.sensor == Sensor::panoramic) {
    sim::PanoramaSettings panorama;
    panorama.bearing_noise_deg = request.bearing_noise_deg;
    station_settings.panorama = panorama;
  }
  if (request.sensor == Sensor::range_ring) {
    sim::RangeRingSettings ring;
    ring.relative_error = request.range_error;
    station_settings.range_ring = ring;
  }
  const Vector2d start = world.objects.at(plan.start) + plan.start_offset;
  Station station(world, station_settings, sim::Pose2{start.x(), start.y(), 0});

  JourneyResult result;
  TruthWitness witness(station, plan, result.held);
  Equipment equipment{station.camera(), station.arm(), station.compass()};
  result.travel = system.travel(plan, equipment, witness);
  result.frames = result.travel.frames;
  result.arm = station.log();
  result.outcome = classify(judge(result.held, plan, result.travel));
  return result;
}

}  // namespace neopipe::rig
