// The navigator's eye: the engine's blob graph on onboard frames, centroids in window millimetres.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "nav/navigator/navigator.hpp"
#include "sim/realism.hpp"
#include "sim/world.hpp"
#include "sim_rig.hpp"

namespace neopipe::nav::navigator {
namespace {

using test_rig::Rig;

// Every object whose centre lies strictly inside the window, in window coordinates.
std::vector<Eigen::Vector2d> truth_in_window(const sim::World& world, const Eigen::Vector2d& origin, double a) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : world.objects) {
    const Eigen::Vector2d q = p - origin;
    if (q.x() > 0 && q.x() < a && q.y() > 0 && q.y() < a) out.push_back(q);
  }
  return out;
}

// The eye's error on whole marbles clear of the border and on marbles near it (whether it counts
// them in view or not), over 40 windows of a dense world.
struct CentroidErrors {
  double clear_rms = 0;
  double clear_worst = 0;
  double border_worst = 0;
  int compared = 0;
};

CentroidErrors centroid_errors(sim::Realism realism) {
  sim::WorldRequest request;
  request.objects = 400;
  request.size = {300, 300};
  request.seed = 5;
  test_rig::RigOptions options;
  options.realism = realism;
  Rig rig(sim::generate_world(request), options);
  const double a = rig.config().window.side;
  CentroidErrors e;
  double sum2 = 0;
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector2d origin(20 + 5.3 * i, 30 + 4.1 * i);
    rig.place(origin);
    const Sighting seen = rig.eye().look();
    std::vector<Eigen::Vector2d> all = seen.objects;
    all.insert(all.end(), seen.partial.begin(), seen.partial.end());
    for (const Eigen::Vector2d& q : truth_in_window(rig.world(), origin, a)) {
      // Marbles cut by the border are located less well; the margin keeps the landmarks clear of it.
      const bool clear = q.x() > 2.5 && q.x() < a - 2.5 && q.y() > 2.5 && q.y() < a - 2.5;
      double best = 1e9;
      for (const Eigen::Vector2d& p : clear ? seen.objects : all) best = std::min(best, (p - q).norm());
      if (clear) {
        sum2 += best * best;
        e.clear_worst = std::max(e.clear_worst, best);
        ++e.compared;
      } else {
        e.border_worst = std::max(e.border_worst, best);
      }
    }
    // Nothing seen that is not there.
    for (const Eigen::Vector2d& p : seen.objects) {
      double best = 1e9;
      for (const Eigen::Vector2d& w : rig.world().objects) best = std::min(best, (w - origin - p).norm());
      EXPECT_LT(best, 1.5) << "phantom at " << p.transpose() << " in window " << i;
    }
  }
  e.clear_rms = e.compared > 0 ? std::sqrt(sum2 / e.compared) : 0;
  std::cout << sim::realism_name(realism) << ": whole marbles " << e.compared << ", RMS " << e.clear_rms
            << " mm, worst " << e.clear_worst << " mm; near the border worst " << e.border_worst << " mm\n";
  return e;
}

TEST(Eye, CentroidsMatchTheWorldWithinAFifthOfAMillimetre) {
  const CentroidErrors ideal = centroid_errors(sim::Realism::ideal);
  EXPECT_GT(ideal.compared, 100);
  EXPECT_LT(ideal.clear_worst, 0.2);
  EXPECT_LT(ideal.border_worst, 1.5);
  // Under the rig's realism the camera's lens, the spheres' shading and shadows are not in the
  // eye's model of its camera; a whole marble still comes within a fifth of a millimetre.
  const CentroidErrors rig = centroid_errors(sim::Realism::rig);
  EXPECT_GT(rig.compared, 100);
  EXPECT_LT(rig.clear_worst, 0.2);
  EXPECT_LT(rig.border_worst, 1.5);
}

TEST(Eye, MarblesWhoseCentreIsOutsideTheWindowAreNotSeen) {
  // Three marbles straddling the western border: centres 1 mm outside, 1 mm inside, 2 mm inside.
  sim::World world;
  world.size = {200, 200};
  world.objects = {{99, 110}, {101, 125}, {102, 140}};
  Rig rig(world);
  rig.place({100, 100});
  const Sighting seen = rig.eye().look();
  ASSERT_EQ(seen.objects.size(), 2u);
  for (const Eigen::Vector2d& p : seen.objects) EXPECT_NEAR(p.x(), p.y() < 30 ? 1 : 2, 0.5);
  std::vector<double> ys;
  for (const Eigen::Vector2d& p : seen.objects) ys.push_back(p.y());
  std::sort(ys.begin(), ys.end());
  EXPECT_NEAR(ys[0], 25, 0.5);
  EXPECT_NEAR(ys[1], 40, 0.5);
}

// Marbles at each border and in each corner, from 1.25 mm outside to 2 mm inside: the worst error of
// the centre the eye puts back from the cap it sees, apart from deep corner caps (which show little
// of their marble) and their worst.
struct CutErrors {
  double worst = 0;
  double deep_corner_worst = 0;
};

CutErrors cut_errors(sim::Realism realism) {
  CutErrors e;
  for (double off = -1.25; off <= 2.01; off += 0.25) {
    sim::World world;
    world.size = {300, 300};
    world.objects = {{100 + off, 125},       {150 - off, 125},       {125, 100 + off},       {125, 150 - off},
                     {100 + off, 100 + off}, {150 - off, 150 - off}, {100 + off, 150 - off}, {150 - off, 100 + off}};
    test_rig::RigOptions options;
    options.realism = realism;
    Rig rig(world, options);
    rig.place({100, 100});
    const Sighting seen = rig.eye().look();
    std::vector<Eigen::Vector2d> all = seen.objects;
    all.insert(all.end(), seen.partial.begin(), seen.partial.end());
    EXPECT_EQ(all.size(), world.objects.size()) << "offset " << off;
    for (const Eigen::Vector2d& w : world.objects) {
      const Eigen::Vector2d q = w - Eigen::Vector2d(100, 100);
      double best = 1e9;
      for (const Eigen::Vector2d& p : all) best = std::min(best, (p - q).norm());
      const bool deep_corner = (q.x() < -1 || q.x() > 51) && (q.y() < -1 || q.y() > 51);
      (deep_corner ? e.deep_corner_worst : e.worst) = std::max(deep_corner ? e.deep_corner_worst : e.worst, best);
      // In view exactly when the centre is inside (by more than the lens and shading may shift it).
      const bool inside = q.x() > 0 && q.x() < 50 && q.y() > 0 && q.y() < 50;
      if (std::min({std::abs(q.x()), std::abs(q.y()), std::abs(50 - q.x()), std::abs(50 - q.y())}) > 0.3) {
        const bool seen_inside = std::any_of(seen.objects.begin(), seen.objects.end(),
                                             [&](const Eigen::Vector2d& p) { return (p - q).norm() < 0.5; });
        EXPECT_EQ(seen_inside, inside) << sim::realism_name(realism) << ": marble at " << q.transpose();
      }
    }
  }
  std::cout << sim::realism_name(realism) << ": worst error of a marble cut by the border " << e.worst
            << " mm, of a deep corner cap " << e.deep_corner_worst << " mm\n";
  return e;
}

TEST(Eye, MarblesCutByTheBorderAreLocatedAsWellAsWhole) {
  const CutErrors ideal = cut_errors(sim::Realism::ideal);
  EXPECT_LT(ideal.worst, 0.2);
  EXPECT_LT(ideal.deep_corner_worst, 1.0);
  // The rig's lens, vignetting and shading change a cut marble's cap where the eye assumes an
  // evenly lit disk: a third of a millimetre (the navigator's view margin covers it).
  const CutErrors rig = cut_errors(sim::Realism::rig);
  EXPECT_LT(rig.worst, 0.35);
  EXPECT_LT(rig.deep_corner_worst, 1.0);
}

TEST(Eye, AnEmptyViewShowsNothing) {
  sim::World world;
  world.size = {300, 300};
  world.objects = {{20, 20}};
  Rig rig(world);
  for (int i = 0; i < 20; ++i) {
    rig.place({100 + i, 150 - i});
    EXPECT_TRUE(rig.eye().look().objects.empty()) << "frame " << i;
  }
}

TEST(Eye, CountsFramesAndKeepsTheLastOne) {
  sim::World world;
  world.size = {300, 300};
  world.objects = {{120, 120}};
  Rig rig(world);
  rig.place({100, 100});
  EXPECT_EQ(rig.eye().look().frame, 0);
  const Sighting second = rig.eye().look();
  EXPECT_EQ(second.frame, 1);
  ASSERT_EQ(second.objects.size(), 1u);
  EXPECT_NEAR(second.objects[0].x(), 20, 0.2);
  EXPECT_NEAR(second.objects[0].y(), 20, 0.2);
  EXPECT_EQ(rig.eye().last_frame().image.cols, 256);
}

}  // namespace
}  // namespace neopipe::nav::navigator
