// SceneRenderer against references: the ideal preset is today's MarbleRenderer bit for bit (frames,
// targets, the camera source); its own ray-cast path renders today's disks to a gray level; a
// sphere's outline is area-sampled so that the centroid of a flat-lit render sits within 0.01 px of
// the supersampled silhouette's; the truth's parallax is the geometry's; the same seed gives the
// same pixels; interlaced frames take their rows from two instants; bad settings are one-line
// errors naming the field.

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <thread>

#include "rig_test_support.hpp"
#include "sim/camera_source.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/marble_truth.hpp"
#include "sim/target_renderer.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)

namespace {

std::string error_of(const sim::Rendering& r) {
  try {
    r.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneRenderer, IdealIsTodaysImagesBitForBit) {
  for (const auto& w : {world(400, 7), world(100, 3)}) {
    const sim::Rendering g = sim::rendering_for(sim::Realism::ideal, sim::CameraKind::global);
    const auto global = sim::make_global_camera(w.size, {}, g);
    EXPECT_EQ(global.intrinsics(), sim::make_global_camera(w.size).intrinsics());
    const sim::MarbleRenderer today(sim::ImageModel{}, global.size());
    const sim::SceneRenderer ideal(g, global);
    for (const std::int64_t frame : {0, 5}) {
      EXPECT_EQ(cv::norm(ideal.render(w.objects, w.marble_diameter, global, frame),
                         today.render(w.objects, w.marble_diameter, global, frame), cv::NORM_INF),
                0);
    }
    const sim::CalibrationTarget board{sim::TargetKind::dots, 11, 8, 30, 10};
    const auto pose = sim::target_pose(100, 120, 20, 5, 10, -5);
    EXPECT_EQ(cv::norm(sim::render_target(board, pose, global, ideal, 2),
                       sim::render_target(board, pose, global, today, 2), cv::NORM_INF),
              0);

    const sim::Rendering o = sim::rendering_for(sim::Realism::ideal, sim::CameraKind::onboard);
    const sim::OnboardCameraConfig config = sim::onboard_config_for(o, w.marble_diameter);
    EXPECT_EQ(config.window_plane_z, 0);
    const sim::MarbleRenderer today_onboard(sim::ImageModel{}, {256, 256});
    for (const sim::Pose2 at : {sim::Pose2{250, 250, 0.3}, sim::Pose2{100, 420, -1.2}}) {
      const auto camera = sim::make_onboard_camera(at, config, o);
      const sim::SceneRenderer r(o, camera);
      EXPECT_EQ(
          cv::norm(r.render(w.objects, w.marble_diameter, camera, 3),
                   today_onboard.render(w.objects, w.marble_diameter, sim::make_onboard_camera(at), 3), cv::NORM_INF),
          0);
    }
  }
}

TEST(SceneRenderer, IdealCameraSourceIsTodaysSource) {
  const sim::World w = world(300, 7);
  const std::vector<sim::Pose2> path{{100, 100, 0}, {120, 100, 0.1}, {140, 110, 0.2}};
  const sim::Rendering ideal = sim::rendering_for(sim::Realism::ideal, sim::CameraKind::onboard);
  auto now = sim::onboard_path_source(w, {}, ideal, path, neopipe::pipeline::io::ColorFormat::gray);
  auto today = sim::onboard_path_source(w, {}, sim::ImageModel{}, path, neopipe::pipeline::io::ColorFormat::gray);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(cv::norm(now->next()->image, today->next()->image, cv::NORM_INF), 0);
  std::size_t at = 0;
  auto follow = sim::onboard_camera_source(
      w, {}, ideal, [&] { return path[at++]; }, neopipe::pipeline::io::ColorFormat::gray);
  const sim::MarbleRenderer r(sim::ImageModel{}, {256, 256});
  EXPECT_EQ(cv::norm(follow->next()->image, r.render(w.objects, 5, sim::make_onboard_camera(path[0]), 0), cv::NORM_INF),
            0);
}

TEST(SceneRenderer, RayCastDisksAreTodaysDisks) {
  // Today's settings but interlaced (a still scene: both fields alike) take the ray-cast path. Both
  // area-sample the rim along its tangent (the ray-cast path also corrects for its curvature), so
  // they differ only on rim pixels, where the light changes by 60 gray levels per pixel, and the
  // ray-cast marbles' centroids are as close to the truth as today's.
  const sim::World w = world(400, 7);
  sim::Rendering r = sim::rendering_for(sim::Realism::ideal, sim::CameraKind::global);
  r.sensor.read_noise = 0;
  r.interlace = true;
  const auto camera = sim::make_global_camera(w.size, {}, r);
  const sim::SceneRenderer cast(r, camera);
  ASSERT_FALSE(r.is_image_model());
  const sim::MarbleRenderer today(r.image_model(), camera.size());
  const cv::Mat a = cast.render(w.objects, 5, camera, 0);
  const cv::Mat b = today.render(w.objects, 5, camera, 0);
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double worst = 0;
  cv::minMaxLoc(diff, nullptr, &worst);
  const int beyond_one = cv::countNonZero(diff > 1);
  // Each frame's centroids (examples/marbles.yaml) against the projected centres.
  const auto truth = sim::marble_truth(w.objects, 5, camera, sim::MarbleShape::disk);
  const auto rms_to_truth = [&](const cv::Mat& frame, double& max) {
    const auto found = marble_blobs(frame, 60);
    EXPECT_EQ(found.size(), truth.size());
    double sum2 = 0;
    max = 0;
    for (const auto& t : truth) {
      double nearest = 1e9;
      for (const auto& blob : found) nearest = std::min(nearest, std::hypot(blob.wcx - t.u, blob.wcy - t.v));
      sum2 += nearest * nearest;
      max = std::max(max, nearest);
    }
    return std::sqrt(sum2 / static_cast<double>(truth.size()));
  };
  double max_cast = 0;
  double max_today = 0;
  const double cast_rms = rms_to_truth(a, max_cast);
  const double today_rms = rms_to_truth(b, max_today);
  std::printf(
      "ray-cast disks vs MarbleRenderer: worst %.0f gray levels, %d pixels beyond 1; centroids vs truth: "
      "ray-cast %.4f px RMS (max %.4f), MarbleRenderer %.4f px RMS (max %.4f)\n",
      worst, beyond_one, cast_rms, max_cast, today_rms, max_today);
  EXPECT_LE(worst, 4);
  EXPECT_LT(beyond_one, 2000);  // of 400 marbles' ~25,000 pixels
  EXPECT_LE(cast_rms, today_rms + 0.001);
  EXPECT_LT(max_cast, 0.02);
}

TEST(SceneRenderer, FlatLitSphereCentroidIsTheSilhouettesWithinAHundredthOfAPixel) {
  // Uniform albedo, no light effects, no blur or noise: the render is the outline's area coverage.
  struct Case {
    const char* name;
    sim::CameraKind kind;
    sim::Pose2 pose;            // onboard
    Eigen::Vector2d marble_at;  // world mm
  };
  const std::vector<Case> cases{{"onboard centre", sim::CameraKind::onboard, {250, 250, 0.4}, {250.3, 249.6}},
                                {"onboard corner", sim::CameraKind::onboard, {250, 250, 0.4}, {261.1, 238.7}},
                                {"global centre", sim::CameraKind::global, {}, {251.3, 248.9}},
                                {"global corner", sim::CameraKind::global, {}, {23.7, 478.2}}};
  for (const Case& c : cases) {
    sim::Rendering r = quiet(rig(c.kind));
    r.light.reset();
    r.surfaces.table = 0;
    r.surfaces.marble = 100;
    const sim::World w = one_marble(c.marble_at);
    const auto camera = c.kind == sim::CameraKind::global ? sim::make_global_camera(w.size, {}, r) : onboard(r, c.pose);
    const sim::SceneRenderer renderer(r, camera);
    const cv::Mat light = renderer.radiance(w.objects, 5, camera);
    const auto truth = sim::marble_truth(w.objects, 5, camera).at(0);
    const int half = c.kind == sim::CameraKind::global ? 8 : 20;
    const cv::Rect box(static_cast<int>(truth.u) - half, static_cast<int>(truth.v) - half, 2 * half + 1, 2 * half + 1);
    const cv::Mat reference = supersampled_coverage(camera, {c.marble_at.x(), c.marble_at.y(), 2.5}, 2.5, box, 128);
    const Eigen::Vector2d ours = centroid(light(box), box.tl());
    const Eigen::Vector2d silhouette = centroid(reference, box.tl());
    cv::Mat ours_cover;
    light(box).convertTo(ours_cover, CV_64F, 1.0 / 100);
    const double worst_pixel = cv::norm(ours_cover, reference, cv::NORM_INF);
    std::printf(
        "%s: centroid - silhouette's (%.4f, %.4f) px; silhouette - projected centre (%.4f, %.4f) px; worst "
        "pixel coverage %.4f\n",
        c.name, ours.x() - silhouette.x(), ours.y() - silhouette.y(), silhouette.x() - truth.u,
        silhouette.y() - truth.v, worst_pixel);
    EXPECT_LT((ours - silhouette).norm(), 0.01) << c.name;
    EXPECT_LT(worst_pixel, 0.01) << c.name;
  }
}

TEST(SceneRenderer, TruthParallaxGrowsWithDistanceFromTheNadirAsTheGeometrySays) {
  // A centre h above its contact point, seen from a camera at height H over the nadir, is displaced
  // on the table by h / (H - h) times its horizontal distance from the nadir: in the image, that
  // times the local scale.
  const sim::Rendering r = rig(sim::CameraKind::global);
  const auto camera = sim::make_global_camera({500, 500}, {}, r);
  const Eigen::Vector3d c = camera.centre();
  std::vector<Eigen::Vector2d> marbles;
  for (double x = 20; x <= 480; x += 46) marbles.emplace_back(x, 0.6 * x + 40);
  const auto truth = sim::marble_truth(marbles, 5, camera);
  ASSERT_EQ(truth.size(), marbles.size());
  double previous = -1;
  for (const auto& t : truth) {
    const Eigen::Vector2d p = marbles[static_cast<std::size_t>(t.id)];
    const double distance = (p - c.head<2>()).norm();
    const double expected_mm = 2.5 / (c.z() - 2.5) * distance;
    const auto back = camera.plane_point({t.u, t.v});  // where the centre's ray meets the table
    ASSERT_TRUE(back);
    EXPECT_NEAR((*back - p).norm(), expected_mm, 1e-6);
    const double parallax_px = std::hypot(t.u - t.u0, t.v - t.v0);
    if (distance > previous) {
      EXPECT_GT(parallax_px, 0);
    }
    previous = distance;
  }
  // Flat disks have none.
  for (const auto& t : sim::marble_truth(marbles, 5, camera, sim::MarbleShape::disk)) {
    EXPECT_EQ(t.u, t.u0);
    EXPECT_EQ(t.v, t.v0);
  }
}

TEST(SceneRenderer, OnboardWindowLiesInThePlaneOfTheMarblesCentres) {
  const sim::Rendering r = rig(sim::CameraKind::onboard);
  const sim::OnboardCameraConfig config = sim::onboard_config_for(r, 5);
  EXPECT_EQ(config.window_plane_z, 2.5);
  // Without the lens, the window's corners at the centres' height are the image's corners.
  const sim::Pose2 pose{200, 300, 0.7};
  const auto camera = sim::make_onboard_camera(pose, config);
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const Eigen::Vector3d corner(pose.x + 25 * c - 25 * s, pose.y + 25 * s + 25 * c, 2.5);  // tool (+a/2, +a/2)
  const auto px = camera.project(corner);
  EXPECT_NEAR(px->x(), 255.5, 1e-9);
  EXPECT_NEAR(px->y(), -0.5, 1e-9);
}

TEST(SceneRenderer, SameSeedSamePixelsOtherSeedOrFrameOtherNoise) {
  const sim::World w = world(400, 7);
  sim::Rendering r = rig(sim::CameraKind::onboard);
  const auto camera = onboard(r, {250, 250, 0.3});
  const sim::SceneRenderer a(r, camera);
  const sim::SceneRenderer b(r, onboard(r, {10, 10, 0}));  // another pose at construction: same frames
  r.sensor.seed = 2;
  const sim::SceneRenderer c(r, camera);
  const cv::Mat fa = a.render(w.objects, 5, camera, 4);
  EXPECT_EQ(cv::norm(fa, b.render(w.objects, 5, camera, 4), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(fa, c.render(w.objects, 5, camera, 4), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(fa, a.render(w.objects, 5, camera, 5), cv::NORM_INF), 0);
}

TEST(SceneRenderer, OneRendererOnManyThreadsGivesTheSamePixels) {
  // render() is const and keeps no state between calls: frames rendered concurrently by four
  // threads sharing one renderer are those rendered one after another.
  const sim::World w = world(1000, 3);
  const sim::Rendering r = rig(sim::CameraKind::onboard);
  const auto camera_at = [&](int i) { return onboard(r, {100 + 3.0 * i, 150 + 2.0 * i, 0.05 * i}); };
  const sim::SceneRenderer renderer(r, camera_at(0));
  constexpr int kFrames = 32;
  std::vector<cv::Mat> sequential;
  sequential.reserve(kFrames);
  for (int i = 0; i < kFrames; ++i) sequential.push_back(renderer.render(w.objects, 5, camera_at(i), i));
  std::vector<cv::Mat> concurrent(kFrames);
  std::vector<std::thread> threads;
  threads.reserve(4);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = t; i < kFrames; i += 4)
        concurrent[static_cast<std::size_t>(i)] = renderer.render(w.objects, 5, camera_at(i), i);
    });
  }
  for (auto& t : threads) t.join();
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_EQ(cv::norm(sequential[static_cast<std::size_t>(i)], concurrent[static_cast<std::size_t>(i)], cv::NORM_INF),
              0)
        << "frame " << i;
  }
}

TEST(SceneRenderer, InterlacedFramesTakeOddRowsHalfAFrameLater) {
  const sim::World w = world(1000, 3);
  sim::Rendering r = quiet(rig(sim::CameraKind::onboard));
  r.interlace = true;
  sim::Rendering progressive = r;
  progressive.interlace = false;
  const auto early = onboard(r, {250, 250, 0});
  const auto late = onboard(r, {252, 250, 0});
  const sim::SceneRenderer inter(r, early);
  const sim::SceneRenderer prog(progressive, early);
  const cv::Mat frame = inter.render(w.objects, early, w.objects, late, 5, 0);
  const cv::Mat at_early = prog.render(w.objects, 5, early, 0);
  const cv::Mat at_late = prog.render(w.objects, 5, late, 0);
  double combing = 0;
  for (int y = 0; y < frame.rows; ++y) {
    const cv::Mat expected = (y % 2 == 0 ? at_early : at_late).row(y);
    EXPECT_EQ(cv::norm(frame.row(y), expected, cv::NORM_INF), 0) << "row " << y;
    if (y > 0) combing += cv::norm(frame.row(y), frame.row(y - 1), cv::NORM_L1);
  }
  double smooth = 0;
  for (int y = 1; y < at_early.rows; ++y) smooth += cv::norm(at_early.row(y), at_early.row(y - 1), cv::NORM_L1);
  EXPECT_GT(combing, 1.5 * smooth);  // moving edges comb
  // A still scene: the same frame either way.
  EXPECT_EQ(cv::norm(inter.render(w.objects, 5, early, 0), at_early, cv::NORM_INF), 0);
}

TEST(SceneRenderer, BadSettingsAreOneLineErrorsNamingTheField) {
  sim::Rendering r = rig(sim::CameraKind::global);
  r.sensor.read_noise = -1;
  EXPECT_EQ(error_of(r).rfind("sensor.read_noise: must be", 0), 0U) << error_of(r);
  r = rig(sim::CameraKind::global);
  r.light->position.z() = 0;
  EXPECT_EQ(error_of(r).rfind("light.position: z = 0 mm is at or below the table", 0), 0U) << error_of(r);
  r = rig(sim::CameraKind::global);
  r.sensor.full_well = 0.0;
  EXPECT_EQ(error_of(r), "sensor.full_well: must be > 0 electrons (got 0)");
  r = rig(sim::CameraKind::global);
  r.surfaces.texture = 1.5;
  EXPECT_EQ(error_of(r).rfind("surfaces.texture: must be in [0, 1)", 0), 0U);
  r = rig(sim::CameraKind::global);
  r.defocus.corner = std::nan("");
  EXPECT_EQ(error_of(r).rfind("defocus.corner:", 0), 0U);
  for (const auto& name : {"ideal", "rig", "harsh"}) {
    EXPECT_EQ(sim::realism_name(sim::parse_realism(name)), name);
    for (const auto kind : {sim::CameraKind::global, sim::CameraKind::onboard}) {
      EXPECT_EQ(error_of(sim::rendering_for(sim::parse_realism(name), kind)), "");
    }
  }
  EXPECT_THROW((void)sim::parse_realism("real"), std::invalid_argument);
  // A light below the marbles' tops: the renderer says so, once it knows the diameter.
  r = rig(sim::CameraKind::global);
  r.light->position.z() = 4;
  const auto camera = sim::make_global_camera({500, 500}, {}, r);
  const sim::SceneRenderer renderer(r, camera);
  const std::vector<Eigen::Vector2d> one{{250, 250}};
  EXPECT_THROW((void)renderer.render(one, 5, camera, 0), std::invalid_argument);
  // A camera with other intrinsics than the renderer's.
  EXPECT_THROW((void)renderer.render(one, 5, sim::make_global_camera({500, 500}), 0), std::invalid_argument);
}
