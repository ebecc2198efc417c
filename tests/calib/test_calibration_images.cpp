// Calibration from images, end to end. In the simulator: dot-grid target images from the default
// global camera (lens distortion on, noise on) -> the dot-grid detector -> the full model -> rendered
// marbles through the engine's blob graph -> workspace positions, against the world file's truth:
// per-axis |mean| <= 0.005 mm, sd <= 0.010 mm and max < 0.04 mm, about twice what is measured (issue
// 5's target, |mean| <= 0.05 mm and sd <= 0.15 mm, is thirty times looser). On real photographs: OpenCV's chessboard
// sample set gives the focal length and reprojection RMS of cv::calibrateCamera on the same
// detections within 1%, and the focal length of OpenCV's own sample recipe within 1%.

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/chessboard.hpp"
#include "calib/dot_grid_detector.hpp"
#include "calib/estimate.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/target_renderer.hpp"
#include "sim/world.hpp"

namespace calib = neopipe::calib;
namespace sim = neopipe::sim;
namespace pl = neopipe::pipeline;

namespace {

const std::string kSamples = "/usr/share/doc/opencv-doc/examples/data";

calib::View detected_view(const cv::Mat& img, const sim::CalibrationTarget& t, const std::string& name) {
  const auto found = calib::find_dot_grid(img, t.cols, t.rows);
  EXPECT_TRUE(found) << name;
  calib::View v{name, {}};
  if (!found) throw std::runtime_error(name + ": the dot grid was not found");
  const auto plane = sim::target_points(t);
  for (std::size_t i = 0; i < plane.size(); ++i) v.points.push_back({(*found)[i], plane[i]});
  return v;
}

}  // namespace

TEST(CalibrationImages, SimulatedDotGridMapsMarblesToAHundredthOfAMillimetre) {
  const auto camera = sim::make_global_camera({500, 500});
  const sim::MarbleRenderer renderer(sim::ImageModel{}, camera.size());  // default: lens, noise 2, blur
  const sim::CalibrationTarget grid{sim::TargetKind::dots, 15, 15, 25, 9};
  // The first view lies on the workspace (its first dot at (75, 75), rows East); the rest are raised
  // and tilted, for the lens.
  const std::vector<sim::TargetPose> poses{
      sim::target_pose(75, 75, 0, 0), sim::target_pose(80, 70, 40, 3, 20, 0), sim::target_pose(70, 80, 30, -3, 0, 22),
      sim::target_pose(80, 80, 50, 2, -15, 12), sim::target_pose(75, 70, 20, -2, 12, -15)};
  std::vector<calib::View> views;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    views.push_back(detected_view(sim::render_target(grid, poses[i], camera, renderer, static_cast<std::int64_t>(i)),
                                  grid, "view " + std::to_string(i)));
  }
  ASSERT_EQ(views.front().points.size(), 225U);
  calib::Correspondences workspace = views.front().points;
  for (auto& p : workspace) p.world += Eigen::Vector2d(75, 75);
  const calib::Calibration c = calib::calibrate_full(views, workspace, camera.size());

  sim::WorldRequest q;
  q.objects = 300;
  q.seed = 21;
  const sim::World world = sim::generate_world(q);
  const cv::Mat frame = renderer.render(world.objects, world.marble_diameter, camera, 99);
  const auto graph = pl::load_graph_spec(std::string(NEOPIPE_EXAMPLES_DIR) + "/marbles.yaml");
  const auto blobs =
      std::get<pl::BlobList>(pl::run_frames(pl::compile(graph, pl::standard_kernels()), {frame}).at(0).outputs.at(0));
  ASSERT_EQ(blobs.size(), world.objects.size());
  std::vector<Eigen::Vector2d> pixels;
  for (const auto& b : blobs) pixels.emplace_back(b.wcx, b.wcy);
  const auto mapped = c.to_world(pixels);
  std::vector<Eigen::Vector2d> errors;
  for (const auto& m : mapped) {  // nearest marble of the world file
    Eigen::Vector2d best(1e9, 1e9);
    for (const auto& o : world.objects) {
      if ((m - o).norm() < best.norm()) best = m - o;
    }
    errors.push_back(best);
  }
  const calib::ErrorStats e = calib::error_stats(errors);
  std::printf(
      "marbles via calibration: mean (%+.4f, %+.4f) mm, sd (%.4f, %.4f) mm, rms %.4f, max %.4f; "
      "calibration held-out rms %.4f mm, reprojection %.4f px\n",
      e.mean.x(), e.mean.y(), e.sd.x(), e.sd.y(), e.rms, e.max, c.report.held_out.rms, c.report.reprojection_rms_px);
  // Measured (every input here is seeded, so this is the figure each run gives): mean (-0.0018,
  // +0.0004) mm, sd (0.0050, 0.0050) mm, max 0.0198 mm. The bounds allow about twice that, for other
  // CPUs' and library versions' rounding; issue 5's target (|mean| <= 0.05, sd <= 0.15 mm) would
  // still pass a calibration that had lost its lens model's higher terms (that doubles every figure:
  // mean (-0.0069, -0.0059), sd (0.0103, 0.0109), max 0.066 mm).
  EXPECT_LE(std::abs(e.mean.x()), 0.005);
  EXPECT_LE(std::abs(e.mean.y()), 0.005);
  EXPECT_LE(e.sd.x(), 0.010);
  EXPECT_LE(e.sd.y(), 0.010);
  EXPECT_LT(e.max, 0.04);
}

TEST(CalibrationImages, OpenCVChessboardSamplesMatchCalibrateCamera) {
  std::vector<std::string> files;
  for (int i = 1; i <= 14; ++i) {
    const std::string f = kSamples + "/left" + (i < 10 ? "0" : "") + std::to_string(i) + ".jpg";
    if (std::filesystem::exists(f)) files.push_back(f);
  }
  if (files.size() < 10) GTEST_SKIP() << "OpenCV's sample images are not installed (Debian package opencv-doc)";
  const cv::Size pattern(9, 6);
  // The reference: OpenCV's own sample recipe on the same images.
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<calib::View> views;
  cv::Size size;
  for (const auto& f : files) {
    const cv::Mat img = cv::imread(f, cv::IMREAD_GRAYSCALE);
    size = img.size();
    std::vector<cv::Point2f> c;
    if (!cv::findChessboardCorners(img, pattern, c, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
      continue;
    }
    cv::cornerSubPix(img, c, {11, 11}, {-1, -1}, {cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.01});
    corners.push_back(c);
    auto& o = objects.emplace_back();
    for (int j = 0; j < pattern.height; ++j) {
      for (int i = 0; i < pattern.width; ++i) o.emplace_back(static_cast<float>(i), static_cast<float>(j), 0.0F);
    }
    const auto ours = calib::find_chessboard(img, pattern.width, pattern.height);
    ASSERT_TRUE(ours) << f;
    calib::View v{f, {}};
    for (int j = 0; j < pattern.height; ++j) {
      for (int i = 0; i < pattern.width; ++i) {
        v.points.push_back({(*ours)[static_cast<std::size_t>(j * pattern.width + i)], {i * 1.0, j * 1.0}});
      }
    }
    views.push_back(v);
  }
  ASSERT_GE(views.size(), 10U);
  // OpenCV's sample recipe (11 x 11 refinement window) on the same images.
  cv::Mat k;
  cv::Mat d;
  std::vector<cv::Mat> r;
  std::vector<cv::Mat> t;
  const double recipe_rms = cv::calibrateCamera(objects, corners, size, k, d, r, t);
  // cv::calibrateCamera on our detections: the same numbers, as the issue asks.
  std::vector<std::vector<cv::Point2f>> ours;
  for (const auto& v : views) {
    auto& o = ours.emplace_back();
    for (const auto& p : v.points) o.emplace_back(static_cast<float>(p.pixel.x()), static_cast<float>(p.pixel.y()));
  }
  std::vector<std::vector<cv::Point3f>> our_objects;
  for (const auto& v : views) {
    auto& o = our_objects.emplace_back();
    for (const auto& p : v.points)
      o.emplace_back(static_cast<float>(p.world.x()), static_cast<float>(p.world.y()), 0.0F);
  }
  cv::Mat k2;
  cv::Mat d2;
  const double same_rms = cv::calibrateCamera(our_objects, ours, size, k2, d2, r, t);
  const calib::Calibration c = calib::calibrate_full(views, views.front().points, size);
  const double fx = c.camera_matrix.at<double>(0, 0);
  const double fy = c.camera_matrix.at<double>(1, 1);
  std::printf(
      "OpenCV samples (%zu views): neopipe fx %.2f fy %.2f rms %.4f px; cv::calibrateCamera on the same "
      "detections fx %.2f fy %.2f rms %.4f; OpenCV's sample recipe fx %.2f fy %.2f rms %.4f\n",
      views.size(), fx, fy, c.report.reprojection_rms_px, k2.at<double>(0, 0), k2.at<double>(1, 1), same_rms,
      k.at<double>(0, 0), k.at<double>(1, 1), recipe_rms);
  EXPECT_NEAR(fx, k2.at<double>(0, 0), 0.01 * k2.at<double>(0, 0));
  EXPECT_NEAR(fy, k2.at<double>(1, 1), 0.01 * k2.at<double>(1, 1));
  EXPECT_NEAR(c.report.reprojection_rms_px, same_rms, 0.01 * same_rms);
  // Against the recipe: the focal length agrees within 1%; our corners (a refinement window sized to
  // the board) reproject better.
  EXPECT_NEAR(fx, k.at<double>(0, 0), 0.01 * k.at<double>(0, 0));
  EXPECT_NEAR(fy, k.at<double>(1, 1), 0.01 * k.at<double>(1, 1));
  EXPECT_LE(c.report.reprojection_rms_px, recipe_rms);
}
