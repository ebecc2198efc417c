// Determinism and throughput: the same world, map and seeds give the same journey, frame for frame;
// and the whole loop (render, blob graph, interpret, move) runs well above a thousand frames/s.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <random>

#include "journey.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator {
namespace {

using mapmaker::CostCriterion;
using mapmaker::MapMaker;
using mapmaker::Route;
using test_rig::Journey;
using test_rig::Rig;
using test_rig::RigOptions;

mapmaker::MapMakerOptions map_options() {
  mapmaker::MapMakerOptions o;
  o.window = WindowModel::with_side(50);
  // The band the navigator explains a view in (its view margin): checks the map-maker places closer
  // to a border than that are ones the navigator may see either way, as `neopipe nav` pairs them.
  o.border_tolerance = NavigatorConfig{}.view_margin;
  return o;
}

// Routes between random reachable pairs of a world.
std::vector<Route> routes(const MapMaker& maker, std::size_t objects, int count, std::uint64_t seed) {
  std::vector<Route> out;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(objects) - 1);
  for (int attempt = 0; static_cast<int>(out.size()) < count && attempt < 50 * count; ++attempt) {
    const std::uint32_t a = pick(rng);
    const std::uint32_t b = pick(rng);
    if (a == b) continue;
    try {
      out.push_back(maker.plan(a, b, CostCriterion::ratio));
    } catch (const mapmaker::UnreachableGoal&) {
    }
  }
  return out;
}

TEST(Determinism, SameSeedSameJourney) {
  sim::WorldRequest request;
  request.objects = 60;
  request.size = {300, 300};
  request.seed = 7;
  const sim::World world = sim::generate_world(request);
  const MapMaker maker(test_rig::workspace_of(world), map_options());
  const std::vector<Route> rs = routes(maker, world.objects.size(), 4, 7);
  ASSERT_EQ(rs.size(), 4u);
  int moved = 0;
  for (const Route& route : rs) {
    std::vector<Journey> runs;
    std::vector<sim::Pose2> ends;
    for (const std::uint64_t seed : {11u, 11u, 12u}) {
      RigOptions o;
      o.seed = seed;
      Rig rig(world, o);
      runs.push_back(test_rig::travel(rig, route));
      ends.push_back(rig.pose());
    }
    const JourneyReport& a = runs[0].report;
    const JourneyReport& b = runs[1].report;
    EXPECT_EQ(a.ending, b.ending);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.frames, b.frames);
    EXPECT_EQ(a.recoveries, b.recoveries);
    EXPECT_EQ(a.commanded_travel, b.commanded_travel);  // bit for bit
    ASSERT_EQ(a.entries.size(), b.entries.size());
    for (std::size_t i = 0; i < a.entries.size(); ++i) {
      EXPECT_EQ(a.entries[i].frames, b.entries[i].frames);
      EXPECT_EQ(a.entries[i].measured_qoc, b.entries[i].measured_qoc);
      EXPECT_EQ(a.entries[i].verified, b.entries[i].verified);
    }
    EXPECT_EQ(ends[0].x, ends[1].x);
    EXPECT_EQ(ends[0].y, ends[1].y);
    EXPECT_EQ(ends[0].theta, ends[1].theta);
    // Another seed moves the arm differently: the travel commanded differs (unless nothing moved).
    if (a.commanded_travel > 0) {
      EXPECT_NE(a.commanded_travel, runs[2].report.commanded_travel);
      ++moved;
    }
  }
  EXPECT_GE(moved, 2);
}

// The default world (100 marbles on 500 x 500 mm, window 50 mm) at the default errors:
// journeys between random reachable pairs, the share that ends holding the goal, and the frame rate
// of the whole loop.
TEST(Throughput, DefaultSparseWorld) {
  int journeys = 0;
  int at_goal = 0;
  std::int64_t frames = 0;
  double seconds = 0;
  for (std::uint64_t w = 1; w <= 3; ++w) {
    sim::WorldRequest request;
    request.objects = 100;
    request.size = {500, 500};
    request.seed = w;
    const sim::World world = sim::generate_world(request);
    const MapMaker maker(test_rig::workspace_of(world), map_options());
    for (const Route& route : routes(maker, world.objects.size(), 15, w)) {
      RigOptions o;
      o.seed = 100 * w + static_cast<std::uint64_t>(journeys);
      Rig rig(world, o);
      const Journey j = test_rig::travel(rig, route);
      ++journeys;
      const bool reached = j.report.ending == Ending::arrived && j.final_object == route.goal;
      at_goal += reached;
      if (!reached) {
        std::cout << fmt::format("  world {} {} -> {} seed {} {}: {} (ended near {})\n", w, route.start, route.goal,
                                 o.seed, format_custom_map(route.custom_map), j.report.reason, j.final_object);
      }
      frames += j.report.frames;
      seconds += j.seconds;
    }
  }
  const double rate = static_cast<double>(frames) / seconds;
  std::cout << fmt::format(
      "default sparse world: {} of {} journeys at the goal; {} frames in {:.3f} s: {:.0f} frames/s\n", at_goal,
      journeys, frames, seconds, rate);
  RecordProperty("frames_per_second", static_cast<int>(rate));
  EXPECT_GE(journeys, 40);
  // Measured 44 of 45 (issue 17). The goal rate is guarded with statistical power by
  // tests/rig/test_navigation_rates.cpp (1,000 and more journeys); here 45 journeys only say that
  // nothing broke: more than two misses is a fall no noise explains.
  EXPECT_GE(at_goal, journeys - 2);
  // The frame rate is recorded, not asserted: no timed assertions in tests (neopipe bench and
  // docs/ measure it against a peer in the same run).
}

}  // namespace
}  // namespace neopipe::nav::navigator
