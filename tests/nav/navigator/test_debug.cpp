#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "journey.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator {
namespace {

class Printer final : public Observer {
 public:
  explicit Printer(const test_rig::Rig& rig) : rig_(rig) {}
  void landmark_held(std::size_t entry, const Eigen::Vector2d& p) override {
    const auto [o, d] = rig_.nearest_object(rig_.to_world(p));
    fmt::print("  HELD entry {} object {} ({:.2f})\n", entry, o, d);
  }
  void frame_seen(const pipeline::io::SourceFrame&, const Sighting& s) override {
    std::string line = fmt::format("  frame {} pose ({:.2f},{:.2f},{:.4f}):", s.frame, rig_.pose().x, rig_.pose().y,
                                   rig_.pose().theta);
    for (const auto& p : s.objects) {
      const auto [o, d] = rig_.nearest_object(rig_.to_world(p));
      line += fmt::format(" {}@({:.1f},{:.1f})", o, p.x(), p.y());
    }
    for (const auto& p : s.partial) {
      const auto [o, d] = rig_.nearest_object(rig_.to_world(p));
      line += fmt::format(" cap{}@({:.1f},{:.1f})", o, p.x(), p.y());
    }
    fmt::print("{}\n", line);
  }

 private:
  const test_rig::Rig& rig_;
};

TEST(Debug, One) {
  const char* env = std::getenv("NAV_DEBUG");
  if (!env) GTEST_SKIP();
  int w = 0;
  unsigned a = 0, b = 0;
  int errors = 0;
  int objects = 60;
  double side = 300;
  int seed_base = 100;
  unsigned long rig_seed = 1;
  std::sscanf(env, "%d %u %u %d %d %lf %d %lu", &w, &a, &b, &errors, &objects, &side, &seed_base, &rig_seed);
  sim::WorldRequest request;
  request.objects = objects;
  request.size = {side, side};
  request.seed = static_cast<std::uint64_t>(seed_base + w);
  const sim::World world = sim::generate_world(request);
  mapmaker::MapMakerOptions mo;
  mo.window = WindowModel::with_side(50);
  const mapmaker::MapMaker maker(test_rig::workspace_of(world), mo);
  const mapmaker::Route route = maker.plan(a, b, mapmaker::CostCriterion::ratio);
  fmt::print("{}\n{}", format_custom_map(route.custom_map), mapmaker::route_table(route));
  for (const auto& s : route.steps) {
    const auto q = maker.views().quadrants(s.step.landmark);
    fmt::print("step to {} at ({:.2f},{:.2f}) quadrants SE{} SW{} NE{} NW{}\n", s.step.landmark,
               world.objects[s.step.landmark].x(), world.objects[s.step.landmark].y(), q[0], q[1], q[2], q[3]);
    for (const Corner c : kCorners) {
      std::string l;
      for (auto id : maker.views().visible({s.step.landmark, c})) l += fmt::format(" {}", id);
      fmt::print("   held at {}: {}\n", corner_name(c), l);
    }
  }
  test_rig::RigOptions o;
  if (!errors) o.errors = sim::MotionErrors::none();
  o.seed = rig_seed;
  test_rig::Rig rig(world, o);
  rig.hold(route.start, route.start_corner);
  Printer printer(rig);
  const JourneyReport r = follow(route.custom_map, rig.eye(), rig.arm(), rig.config(), &printer);
  fmt::print("ending {} {}\n", static_cast<int>(r.ending), r.reason);
}

}  // namespace
}  // namespace neopipe::nav::navigator

namespace neopipe::nav::navigator {
namespace {
TEST(Debug, Caps) {
  if (!std::getenv("NAV_DEBUG")) GTEST_SKIP();
  for (double off = -3; off <= 3.01; off += 0.25) {
    sim::World world;
    world.size = {300, 300};
    world.objects = {{100 + off, 120}, {120, 100 + off}, {150 - off, 130}, {130, 150 - off}, {125, 125}};
    test_rig::Rig rig(world);
    rig.place({100, 100});
    const Sighting s = rig.eye().look();
    std::string line = fmt::format("offset {:5.2f}:", off);
    for (const auto& p : s.objects) line += fmt::format(" ({:.2f},{:.2f})", p.x(), p.y());
    for (const auto& p : s.partial) line += fmt::format(" cap({:.2f},{:.2f})", p.x(), p.y());
    fmt::print("{}\n", line);
  }
}
}  // namespace
}  // namespace neopipe::nav::navigator
