// The rig's side of the panoramic sensor: a system that asks for it (CameraRequest::sensor) travels
// with ring images of where the arm really is and a compass; the station renders them at the arm's
// true (noisy) pose, refuses to be an onboard camera too, and tells whether the tool keeps clear of
// the marbles.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "nav/common/panorama_reading.hpp"
#include "rig/journey.hpp"
#include "rig/navigation_system.hpp"
#include "rig/station.hpp"
#include "sim/panorama.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
namespace nav = neopipe::nav;
namespace sim = neopipe::sim;
using Eigen::Vector2d;

constexpr double kDegree = std::numbers::pi / 180;

sim::World world() {
  sim::World w;
  w.size = {300, 300};
  w.objects = {{50, 50}, {250, 60}, {150, 250}, {60, 200}};
  return w;
}

double angle_diff(double a, double b) {
  return std::fmod(a - b + 540.0, 360.0) - 180.0;
}

TEST(PanoramaStation, RendersTheRingWhereTheArmReallyIs) {
  const sim::World w = world();
  rig::StationSettings settings;
  settings.panorama = sim::PanoramaSettings{};
  settings.seed = 5;
  rig::Station station(w, settings, {100, 100, 0});
  EXPECT_THROW((void)station.onboard_camera(), std::logic_error);
  ASSERT_NE(station.compass(), nullptr);
  nav::PanoramaReader reader({w.marble_diameter / 2, 0});
  for (int step = 0; step < 4; ++step) {
    const auto frame = station.camera().next();
    ASSERT_TRUE(frame.has_value());
    ASSERT_EQ(frame->image.type(), CV_16SC1);
    const sim::Pose2 truth = station.tool();  // the arm's true pose, after its errors
    const auto seen = reader.read(frame->image);
    const auto expected = sim::marbles_in_view(w, truth, 600);
    ASSERT_EQ(seen.size(), expected.size());
    for (std::size_t i = 0; i < seen.size(); ++i) {
      EXPECT_EQ(seen[i].id, expected[i].id);
      EXPECT_LT(std::abs(angle_diff(seen[i].bearing_deg, expected[i].bearing_deg)), 0.2);
    }
    const nav::CompassReading c = station.compass()->read();
    EXPECT_EQ(c.sigma_deg, 1.0);
    EXPECT_LT(std::abs(angle_diff(c.heading_deg, truth.theta / kDegree)), 5.0);
    ASSERT_TRUE(station.arm().move_relative(20, 5, 0.3));
  }
  EXPECT_TRUE(station.tool_keeps_clear());
  station.place_tool({55, 50, 0});
  EXPECT_FALSE(station.tool_keeps_clear());
}

TEST(PanoramaStation, AnOnboardStationHasNoCompass) {
  const sim::World w = world();
  rig::Station station(w, rig::StationSettings{}, {100, 100, 0});
  EXPECT_EQ(station.compass(), nullptr);
  EXPECT_EQ(station.onboard_camera().next()->image.type(), CV_8UC1);
}

// A system that asks for the panoramic sensor and only looks: it records what its equipment was.
class Looker final : public rig::NavigationSystem {
 public:
  struct Seen {
    int type = -1;
    bool compass = false;
    std::size_t sightings = 0;
    double goal_bearing = -1;
  };
  explicit Looker(Seen& seen) : seen_(seen) {}
  [[nodiscard]] std::string name() const override { return "looker"; }
  [[nodiscard]] rig::CameraRequest camera() const override {
    rig::CameraRequest r;
    r.sensor = rig::Sensor::panoramic;
    return r;
  }
  [[nodiscard]] std::unique_ptr<rig::Plan> plan(std::uint32_t from, std::uint32_t to) const override {
    auto p = std::make_unique<rig::Plan>();
    p->start = from;
    p->goal = to;
    p->landmarks = {from, to};
    p->start_offset = {20, 0};  // beside the start marble, clear of it
    return p;
  }
  rig::Travel travel(const rig::Plan& plan, rig::Equipment& equipment, rig::Witness& witness) const override {
    const auto frame = equipment.camera.next();
    seen_.type = frame->image.type();
    seen_.compass = equipment.compass != nullptr;
    nav::PanoramaReader reader({2.5, 0});
    const auto sightings = reader.read(frame->image);
    seen_.sightings = sightings.size();
    for (const auto& s : sightings) {
      if (s.id == plan.goal) seen_.goal_bearing = s.bearing_deg;
    }
    witness.landmark_claimed(0, {-20, 0});
    rig::Travel t;
    t.ending = rig::Ending::lost;
    return t;
  }

 private:
  Seen& seen_;
};

TEST(PanoramaStation, AJourneyHandsTheSystemThePanoramicSensor) {
  const sim::World w = world();
  Looker::Seen seen;
  const Looker looker(seen);
  const auto plan = looker.plan(0, 1);
  (void)rig::run_journey(looker, *plan, w, {});
  EXPECT_EQ(seen.type, CV_16SC1);
  EXPECT_TRUE(seen.compass);
  EXPECT_EQ(seen.sightings, 4U);
  // The goal (250, 60) from the tool at (70, 50), heading 0.
  const double truth = std::atan2(10.0, 180.0) / kDegree;
  EXPECT_LT(std::abs(angle_diff(seen.goal_bearing, truth)), 0.2);
}

}  // namespace
