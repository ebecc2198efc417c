// Journeys: the navigator follows custom maps the map-maker wrote, on the simulated arm through its
// onboard camera, and ends holding the goal (checked against ground truth).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <random>

#include "journey.hpp"
#include "sim/world.hpp"

namespace neopipe::nav::navigator {
namespace {

using mapmaker::CostCriterion;
using mapmaker::MapMaker;
using mapmaker::MapMakerOptions;
using mapmaker::Route;
using test_rig::Journey;
using test_rig::Rig;
using test_rig::RigOptions;

MapMakerOptions map_options(double a = 50) {
  MapMakerOptions o;
  o.window = WindowModel::with_side(a);
  return o;
}

// Checks every landmark the navigator held against the one the map-maker planned.
void expect_route_followed(const Rig& rig, const Route& route, const Journey& j) {
  ASSERT_EQ(j.report.ending, Ending::arrived) << j.report.reason << "\n" << format_custom_map(route.custom_map);
  ASSERT_EQ(j.held.size(), route.steps.size() + 1);
  EXPECT_EQ(rig.nearest_object(j.held[0].second).first, route.start);
  for (std::size_t k = 0; k < route.steps.size(); ++k) {
    const auto [object, offset] = rig.nearest_object(j.held[k + 1].second);
    EXPECT_EQ(object, route.steps[k].step.landmark)
        << "entry " << k + 1 << " of " << format_custom_map(route.custom_map);
    EXPECT_LT(offset, 1.0);
  }
  EXPECT_EQ(j.final_object, route.goal);
}

// A chain of marbles a window apart, then a gap only a trajectory crosses.
sim::World chain_world() {
  sim::World w;
  w.size = {400, 400};
  w.objects = {{60, 60},   {90, 75},   {100, 110}, {130, 125}, {125, 160},
               {160, 170}, {250, 200}, {285, 225}, {300, 260}, {330, 250}};
  return w;
}

TEST(Journeys, HandMadeWorldEveryLandmarkAsPlanned) {
  const sim::World world = chain_world();
  const MapMaker maker(test_rig::workspace_of(world), map_options());
  for (const auto& [start, goal] : {std::pair{0u, 5u}, std::pair{5u, 0u}, std::pair{0u, 9u}, std::pair{9u, 1u}}) {
    Route route;
    try {
      route = maker.plan(start, goal, CostCriterion::distance);
    } catch (const mapmaker::UnreachableGoal&) {
      ADD_FAILURE() << start << " -> " << goal << " unreachable";
      continue;
    }
    for (const bool errors : {false, true}) {
      RigOptions o;
      if (!errors) o.errors = sim::MotionErrors::none();
      Rig rig(world, o);
      SCOPED_TRACE(
          fmt::format("{} -> {} {}, motion errors {}", start, goal, format_custom_map(route.custom_map), errors));
      const Journey j = test_rig::travel(rig, route);
      expect_route_followed(rig, route, j);
      EXPECT_GT(j.report.frames, 0);
      EXPECT_EQ(j.report.entries.size(), route.custom_map.entries.size());
    }
  }
}

struct Tally {
  int journeys = 0;
  int at_goal = 0;
  int arrived = 0;
  std::int64_t frames = 0;
  double seconds = 0;
  std::vector<std::string> failures;
};

Tally random_journeys(int worlds, int per_world, const RigOptions& rig_options, int objects = 60, double side = 300) {
  Tally t;
  for (int w = 0; w < worlds; ++w) {
    sim::WorldRequest request;
    request.objects = objects;
    request.size = {side, side};
    request.seed = 100 + static_cast<std::uint64_t>(w);
    const sim::World world = sim::generate_world(request);
    const MapMaker maker(test_rig::workspace_of(world), map_options());
    std::mt19937_64 rng(request.seed);
    std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(objects) - 1);
    int done = 0;
    for (int attempt = 0; done < per_world && attempt < 20 * per_world; ++attempt) {
      const std::uint32_t a = pick(rng);
      const std::uint32_t b = pick(rng);
      if (a == b) continue;
      Route route;
      try {
        route = maker.plan(a, b, CostCriterion::ratio);
      } catch (const mapmaker::UnreachableGoal&) {
        continue;
      }
      ++done;
      RigOptions o = rig_options;
      o.seed = rig_options.seed + static_cast<std::uint64_t>(1000 * w + done);
      Rig rig(world, o);
      const Journey j = test_rig::travel(rig, route);
      ++t.journeys;
      t.frames += j.report.frames;
      t.seconds += j.seconds;
      const bool arrived = j.report.ending == Ending::arrived;
      t.arrived += arrived;
      t.at_goal += arrived && j.final_object == route.goal;
      if (!(arrived && j.final_object == route.goal)) {
        t.failures.push_back(fmt::format("world {} {} -> {}: {} {} ended at {}", w, a, b,
                                         format_custom_map(route.custom_map), j.report.reason, j.final_object));
      }
    }
  }
  return t;
}

TEST(Journeys, RandomRoutesReachTheGoal) {
  for (const bool errors : {false, true}) {
    RigOptions o;
    if (!errors) o.errors = sim::MotionErrors::none();
    const Tally t = random_journeys(4, 10, o);
    for (const std::string& f : t.failures) std::cout << "  " << f << "\n";
    std::cout << fmt::format(
        "motion errors {}: {} of {} journeys at the goal ({} arrived), {} frames, {:.0f} frames/s\n", errors, t.at_goal,
        t.journeys, t.arrived, t.frames, t.frames / t.seconds);
    EXPECT_GE(t.journeys, 30);
    // Measured 39 of 40 with and without motion errors (issue 17). The goal rate is guarded with
    // statistical power by tests/rig/test_navigation_rates.cpp; 40 journeys only say that nothing
    // broke: more than two misses is a fall no noise explains.
    EXPECT_GE(t.at_goal, t.journeys - 2);
  }
}

}  // namespace
}  // namespace neopipe::nav::navigator
