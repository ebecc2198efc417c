// The rig's survey through the global camera under each realism: every marble found under its own
// id, the parallax of the spheres' height removed, the lamp's lean on the centroids measured on the
// check plate and taken out, the error within 0.05 mm, and the sigma told to the map-maker honest.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "calib/plane_pose.hpp"
#include "rig/global_camera.hpp"
#include "rig/survey.hpp"
#include "sim/marble_truth.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace {
namespace rig = neopipe::rig;
namespace sim = neopipe::sim;
using Eigen::Vector2d;

sim::World default_world(std::uint64_t seed) {
  sim::WorldRequest q;
  q.objects = 100;
  q.seed = seed;
  return sim::generate_world(q);
}

// Sessions shared by this suite's processes: each test runs in a process of its own under ctest.
rig::SurveySettings settings(sim::Realism realism, std::uint64_t seed) {
  rig::SurveySettings s;
  s.camera.realism = realism;
  s.camera.seed = seed;
  s.cache_dir = std::filesystem::path(::testing::TempDir()) / "neopipe_rig_tests_sessions";
  return s;
}

TEST(Survey, RigRealismWithinFiveHundredthsOfAMillimetre) {
  for (const std::uint64_t seed : {1, 2}) {
    const sim::World world = default_world(seed);
    const rig::Survey s = rig::global_camera_survey(world, settings(sim::Realism::rig, seed));
    SCOPED_TRACE(::testing::Message() << "seed " << seed << ": RMS " << s.rms_error << " mm, max " << s.max_error
                                      << ", told sigma " << s.sigma);
    EXPECT_EQ(s.method, "global_camera");
    EXPECT_EQ(s.realism, "rig");
    ASSERT_EQ(s.workspace.objects.size(), world.objects.size());
    EXPECT_LT(s.rms_error, 0.05);
    EXPECT_LT(s.max_error, 0.15);
    EXPECT_GT(s.rms_error, 0.002);  // a real measurement, not the truth handed over
  }
}

// The default world under the rig's realism: its calibration session, the camera and where every
// marble's centre and contact point truly project.
class RigSurveyOfTheDefaultWorld : public ::testing::Test {
 protected:
  const sim::World world = default_world(1);
  const rig::SurveySettings s = settings(sim::Realism::rig, 1);
  const rig::GlobalCameraSession session = rig::global_camera_session(world, s);
  const rig::GlobalCameraRig rig = rig::make_global_camera_rig(world.size, s.camera);
  const std::vector<sim::MarbleTruth> truth =
      sim::marble_truth(world.objects, world.marble_diameter, rig.camera, rig.rendering.shape);
};

// The spheres' centres are a radius above the table: the global camera sees them displaced from
// their contact points by up to ~0.6 mm towards the image's edges (the u0, v0 of the truth). Mapping
// the centroids as if they lay on the table keeps that parallax; the survey maps them at their
// height and does not.
TEST_F(RigSurveyOfTheDefaultWorld, RemovesTheParallaxOfTheSpheresHeight) {
  ASSERT_EQ(truth.size(), world.objects.size());
  double parallax = 0;
  std::vector<Vector2d> centres;
  for (const auto& t : truth) {
    parallax = std::max(parallax, std::hypot(t.u - t.u0, t.v - t.v0));
    centres.emplace_back(t.u, t.v);
  }
  EXPECT_GT(parallax, 0.8);  // px: half a millimetre and more at the edges
  // The true centres' projections, mapped both ways: on the table (the parallax stays) and at the
  // marbles' height through the calibrated model (it goes).
  const auto on_table = neopipe::calib::to_world_at_height(session.calibration, centres, -session.plane_height);
  const auto at_height =
      neopipe::calib::to_world_at_height(session.calibration, centres, session.marble_height - session.plane_height);
  double flat_worst = 0;
  double height2 = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Vector2d w = world.objects[static_cast<std::size_t>(truth[i].id)];
    flat_worst = std::max(flat_worst, (on_table[i] - w).norm());
    height2 += (at_height[i] - w).squaredNorm();
  }
  EXPECT_GT(flat_worst, 0.4);
  // What is left is the calibration's: a lens its model cannot fit exactly.
  EXPECT_LT(std::sqrt(height2 / static_cast<double>(truth.size())), 0.02);
}

// The lamp pulls the weighted centroids by a third of a pixel; the check plate measures that lean
// and the survey removes it, to about the centroids' noise.
TEST_F(RigSurveyOfTheDefaultWorld, TheLampsLeanIsMeasuredAndRemoved) {
  const sim::SceneRenderer renderer(rig.rendering, rig.camera);
  const auto centroids =
      rig::marble_centroids(renderer.render(world.objects, world.marble_diameter, rig.camera, rig::kWorldFrame));
  ASSERT_EQ(centroids.size(), truth.size());
  Vector2d raw_mean = Vector2d::Zero();
  double corrected2 = 0;
  int n = 0;
  for (const auto& t : truth) {
    const Vector2d centre(t.u, t.v);
    const Vector2d* nearest = &centroids.front();
    for (const Vector2d& c : centroids) {
      if ((c - centre).norm() < (*nearest - centre).norm()) nearest = &c;
    }
    raw_mean += *nearest - centre;
    corrected2 += (session.bias.correct(*nearest) - centre).squaredNorm();
    ++n;
  }
  raw_mean /= n;
  EXPECT_GT(raw_mean.norm(), 0.2);                     // px: the lean, towards the lamp
  EXPECT_LT(std::sqrt(corrected2 / n), 0.05);          // px, after the plate's correction
  EXPECT_LT(session.bias_held_out_px.rms, 0.05);       // what the plate itself says of it
  EXPECT_GT(session.bias.at({640, 480}).norm(), 0.2);  // the field is the lean
}

// The sigma told to the map-maker comes from the plate, never from the world's truth; over several
// seeds, sqrt(2) of it is within a quarter of the true 2-D RMS error of the surveyed marbles.
TEST(Survey, TheToldSigmaIsHonest) {
  for (const std::uint64_t seed : {3, 4, 5}) {
    const sim::World world = default_world(seed);
    const rig::Survey s = rig::global_camera_survey(world, settings(sim::Realism::rig, seed));
    const double told = std::sqrt(2.0) * s.sigma;
    SCOPED_TRACE(::testing::Message() << "seed " << seed << ": told sqrt(2) sigma " << told << " mm, true RMS "
                                      << s.rms_error << " mm");
    EXPECT_GT(told, 0.75 * s.rms_error);
    EXPECT_LT(told, 1.25 * s.rms_error);
  }
}

TEST(Survey, IdealRealismAsBefore) {
  const sim::World world = default_world(1);
  const rig::Survey s = rig::global_camera_survey(world, settings(sim::Realism::ideal, 7));
  EXPECT_EQ(s.realism, "ideal");
  ASSERT_TRUE(s.session.has_value());
  EXPECT_EQ(s.session->plane_height, 0);
  EXPECT_EQ(s.session->marble_height, 0);
  EXPECT_LT(s.rms_error, 0.03);
  EXPECT_LT(s.max_error, 0.1);
  EXPECT_GT(s.rms_error, 0);
  EXPECT_EQ(rig::global_camera_survey(world, settings(sim::Realism::ideal, 7)).workspace.objects, s.workspace.objects);
}

TEST(Survey, RefusesMarblesItCannotTellApart) {
  sim::World w;
  w.size = {500, 500};
  w.objects = {{100, 100}, {105, 100}, {300, 300}};  // the first two touch
  EXPECT_THROW(rig::global_camera_survey(w, settings(sim::Realism::rig, 1)), rig::SurveyError);
}

}  // namespace
