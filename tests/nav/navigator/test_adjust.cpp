// Adjust: visual servoing brings a landmark to a window corner within tolerance in a few frames,
// whatever the arm's motion and rotation errors (checked against where the landmark really is).

#include <gtest/gtest.h>

#include "nav/navigator/pilot.hpp"
#include "sim/realism.hpp"
#include "sim/world.hpp"
#include "sim_rig.hpp"

namespace neopipe::nav::navigator {
namespace {

using test_rig::Rig;
using test_rig::RigOptions;

sim::MotionErrors scaled(double k) {
  sim::MotionErrors e;
  e.translation_sigma0 *= k;
  e.along_per_mm *= k;
  e.across_per_mm *= k;
  e.rotation_sigma0 *= k;
  e.rotation_per_mm *= k;
  e.rotation_per_rad *= k;
  return e;
}

// `landmark_error`: how far the eye may see the landmark from where it is (its error on whole
// marbles near a corner under that realism: test_eye.cpp).
void expect_convergence(sim::Realism realism, double landmark_error) {
  sim::World world;
  world.size = {300, 300};
  world.objects = {{150, 150}, {170, 160}, {135, 128}};
  for (const double k : {0.0, 1.0, 5.0}) {
    int worst_moves = 0;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      RigOptions o;
      o.errors = scaled(k);
      o.seed = seed;
      o.realism = realism;
      Rig rig(world, o);
      rig.hold(0, Corner::SW);
      JourneyReport report;
      detail::Pilot pilot(rig.eye(), rig.arm(), rig.config(), nullptr, report);
      pilot.look();
      const auto start = detail::nearest(pilot.sighting().objects, rig.config().window.corner_point(Corner::SW), 1.0);
      ASSERT_TRUE(start);
      Eigen::Vector2d landmark = pilot.sighting().objects[*start];
      for (const Corner c : {Corner::NE, Corner::SE, Corner::NW, Corner::SW, Corner::NE}) {
        const int before = rig.moves();
        ASSERT_FALSE(detail::adjust(pilot, landmark, c)) << "errors x" << k << " seed " << seed;
        const int moves = rig.moves() - before;
        worst_moves = std::max(worst_moves, moves);
        const Eigen::Vector2d truth = rig.to_window(world.objects[0]);
        const Eigen::Vector2d target = rig.config().window.corner_point(c);
        EXPECT_LT((truth - target).norm(), rig.config().adjust_tolerance + landmark_error)
            << corner_name(c) << " errors x" << k << " seed " << seed;
        EXPECT_LT((landmark - truth).norm(), landmark_error);
      }
    }
    // One move without errors; a correction or two with them.
    EXPECT_LE(worst_moves, k == 0 ? 1 : 4) << "errors x" << k;
  }
}

TEST(Adjust, ConvergesToEveryCornerDespiteMotionErrors) {
  expect_convergence(sim::Realism::ideal, 0.1);
  expect_convergence(sim::Realism::rig, 0.25);
}

TEST(Adjust, FailsAwareWhenTheLandmarkCannotBeTracked) {
  sim::World world;
  world.size = {300, 300};
  world.objects = {{150, 150}};
  RigOptions o;
  o.errors = sim::MotionErrors::none();
  Rig rig(world, o);
  rig.hold(0, Corner::SW);
  JourneyReport report;
  detail::Pilot pilot(rig.eye(), rig.arm(), rig.config(), nullptr, report);
  pilot.look();
  // A landmark believed where nothing is: after the move nothing is where it should be.
  Eigen::Vector2d phantom(25, 25);
  const auto failure = detail::adjust(pilot, phantom, Corner::NE);
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->ending, Ending::lost);
}

}  // namespace
}  // namespace neopipe::nav::navigator
