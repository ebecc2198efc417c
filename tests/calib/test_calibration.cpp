// Calibrations against known cameras: the full model recovers the simulator's intrinsics from
// synthetic target views and maps workspace points back to within hundredths of a millimetre; the
// homography is exact on a lens-free camera; the file round-trips through OpenCV's own FileStorage;
// bad files and degenerate input are refused with the cause.

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/LU>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/core/persistence.hpp>

#include "calib/calibration.hpp"
#include "calib/estimate.hpp"
#include "calib/plane_pose.hpp"
#include "sim/cameras.hpp"
#include "sim/random.hpp"
#include "sim/target_renderer.hpp"

namespace calib = neopipe::calib;
namespace sim = neopipe::sim;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()))).string();
}

// The target's points seen by `camera` at `pose`, with Gaussian pixel noise.
calib::Correspondences view_of(const sim::CalibrationTarget& t, const sim::TargetPose& pose,
                               const sim::PinholeCamera& camera, double noise_px, sim::Random& rng) {
  const auto plane = sim::target_points(t);
  const auto px = sim::projected_target_points(t, pose, camera);
  calib::Correspondences out;
  for (std::size_t i = 0; i < plane.size(); ++i) {
    out.push_back({px[i] + Eigen::Vector2d(rng.normal(0, noise_px), rng.normal(0, noise_px)), plane[i]});
  }
  return out;
}

// The workspace view: the target flat at (x0, y0), turned theta; its points in workspace mm.
calib::Correspondences on_workspace(const calib::Correspondences& view, double x0, double y0, double theta_deg) {
  const double a = theta_deg * 3.141592653589793 / 180;
  calib::Correspondences out = view;
  for (auto& p : out) {
    const Eigen::Vector2d s = p.world;
    p.world = {x0 + std::cos(a) * s.x() - std::sin(a) * s.y(), y0 + std::sin(a) * s.x() + std::cos(a) * s.y()};
  }
  return out;
}

struct Synthetic {
  sim::PinholeCamera camera = sim::make_global_camera({500, 500});
  std::vector<calib::View> views;
  calib::Correspondences workspace;
};

Synthetic synthetic_views(double noise_px) {
  Synthetic s;
  const sim::CalibrationTarget t{sim::TargetKind::dots, 15, 15, 30, 10};
  sim::Random rng(3);
  const auto flat = view_of(t, sim::target_pose(40, 40, 0, 0), s.camera, noise_px, rng);
  s.views.push_back({"flat", flat});
  s.workspace = on_workspace(flat, 40, 40, 0);
  const std::vector<sim::TargetPose> tilted{
      sim::target_pose(60, 80, 60, 10, 25, 0), sim::target_pose(90, 50, 40, -15, 0, 30),
      sim::target_pose(30, 100, 80, 35, -20, 15), sim::target_pose(120, 120, 30, -40, 15, -25)};
  for (std::size_t i = 0; i < tilted.size(); ++i) {
    s.views.push_back({"tilted " + std::to_string(i), view_of(t, tilted[i], s.camera, noise_px, rng)});
  }
  return s;
}

}  // namespace

TEST(Calibration, FullModelRecoversTheSimulatedCamera) {
  const Synthetic s = synthetic_views(0.05);
  const calib::Calibration c = calib::calibrate_full(s.views, s.workspace, s.camera.size());
  const auto& k = s.camera.intrinsics();
  EXPECT_NEAR(c.camera_matrix.at<double>(0, 0), k.fx, 0.002 * k.fx);
  EXPECT_NEAR(c.camera_matrix.at<double>(1, 1), k.fy, 0.002 * k.fy);
  EXPECT_NEAR(c.camera_matrix.at<double>(0, 2), k.cx, 2.0);
  EXPECT_NEAR(c.camera_matrix.at<double>(1, 2), k.cy, 2.0);
  EXPECT_NEAR(c.distortion_coefficients.at<double>(0), k.distortion[0], 0.01);
  EXPECT_LT(c.report.reprojection_rms_px, 0.1);
  // Anywhere on the workspace, not just on the target: the lens is modelled.
  sim::Random rng(9);
  std::vector<Eigen::Vector2d> truth;
  std::vector<Eigen::Vector2d> pixels;
  for (int i = 0; i < 500; ++i) {
    truth.emplace_back(rng.uniform(0, 500), rng.uniform(0, 500));
    pixels.push_back(*s.camera.project({truth.back().x(), truth.back().y(), 0}));
  }
  const auto mapped = c.to_world(pixels);
  std::vector<Eigen::Vector2d> errors;
  for (std::size_t i = 0; i < truth.size(); ++i) errors.push_back(mapped[i] - truth[i]);
  const calib::ErrorStats e = calib::error_stats(errors);
  std::printf("full model, whole workspace: mean (%.4f, %.4f) sd (%.4f, %.4f) rms %.4f max %.4f mm\n", e.mean.x(),
              e.mean.y(), e.sd.x(), e.sd.y(), e.rms, e.max);
  EXPECT_LT(e.rms, 0.05);
  // And the model that ignores the lens is worse, and the report says so.
  EXPECT_GT(c.report.homography_held_out_rms, c.report.full_held_out_rms);
  EXPECT_EQ(c.report.views_used, 5);
}

TEST(Calibration, HomographyIsExactWithoutALens) {
  sim::GlobalCameraConfig config;
  config.distortion = {};
  const auto camera = sim::make_global_camera({500, 500}, config);
  calib::Correspondences points;
  for (double x = 10; x <= 490; x += 40) {
    for (double y = 10; y <= 490; y += 40) points.push_back({*camera.project({x, y, 0}), {x, y}});
  }
  const calib::Calibration c = calib::calibrate_homography(points, camera.size());
  EXPECT_LT(c.report.fit.max, 1e-6);
  EXPECT_LT(c.report.held_out.max, 1e-6);
  EXPECT_LT(c.report.reprojection_rms_px, 1e-6);
  EXPECT_EQ(c.report.points_rejected, 0);
  const auto back = c.to_pixel({{250, 250}});
  EXPECT_LT((back[0] - *camera.project({250, 250, 0})).norm(), 1e-6);
}

TEST(Calibration, FileRoundTripsThroughOpenCV) {
  const Synthetic s = synthetic_views(0.05);
  const calib::Calibration c = calib::calibrate_full(s.views, s.workspace, s.camera.size());
  const std::string path = temp_path("calib") + ".yaml";
  calib::save_calibration(c, path);
  {
    cv::FileStorage fs(path, cv::FileStorage::READ);  // what an OpenCV user does
    ASSERT_TRUE(fs.isOpened());
    cv::Mat k;
    cv::Mat d;
    cv::Mat h;
    cv::Size size;
    std::string model;
    double rms = 0;
    fs["camera_matrix"] >> k;
    fs["distortion_coefficients"] >> d;
    fs["image_to_world"] >> h;
    fs["image_size"] >> size;
    fs["model"] >> model;
    fs["reprojection_rms_px"] >> rms;
    EXPECT_EQ(cv::norm(k, c.camera_matrix, cv::NORM_INF), 0);
    EXPECT_EQ(cv::norm(d, c.distortion_coefficients, cv::NORM_INF), 0);
    EXPECT_EQ(h.at<double>(1, 2), c.image_to_world(1, 2));
    EXPECT_EQ(size, c.image_size);
    EXPECT_EQ(model, "full");
    EXPECT_EQ(rms, c.report.reprojection_rms_px);
  }
  const calib::Calibration r = calib::load_calibration(path);
  std::filesystem::remove(path);
  EXPECT_EQ(r.model, calib::Model::full);
  EXPECT_EQ(r.image_to_world, c.image_to_world);
  EXPECT_EQ(r.report.held_out.sd, c.report.held_out.sd);
  EXPECT_EQ(r.report.points_used, c.report.points_used);
  const auto a = c.to_world({{100, 200}});
  const auto b = r.to_world({{100, 200}});
  EXPECT_EQ(a[0], b[0]);
}

TEST(Calibration, BadFilesNameTheKey) {
  const std::string path = temp_path("bad_calib") + ".yaml";
  const auto error_of = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      (void)calib::load_calibration(path);
    } catch (const calib::CalibrationError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("%YAML:1.0\n---\nmodel: homography\nimage_size: [640, 480]\n").find("'image_to_world'"),
            std::string::npos);
  EXPECT_NE(error_of("%YAML:1.0\n---\nmodel: fancy\n").find("'model'"), std::string::npos);
  EXPECT_NE(error_of("this is not yaml: [").find("bad_calib"), std::string::npos);
  EXPECT_NE(error_of("%YAML:1.0\n---\nmodel: full\nimage_size: [640, 480]\nimage_to_world: !!opencv-matrix\n"
                     "  rows: 3\n  cols: 3\n  dt: d\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n")
                .find("'camera_matrix'"),
            std::string::npos);
  std::filesystem::remove(path);
  EXPECT_THROW((void)calib::load_calibration("/nonexistent/calib.yaml"), calib::CalibrationError);
}

TEST(Calibration, TooFewViewsOrPointsAreRefused) {
  const Synthetic s = synthetic_views(0.05);
  const std::vector<calib::View> two(s.views.begin(), s.views.begin() + 2);
  EXPECT_THROW((void)calib::calibrate_full(two, s.workspace, s.camera.size()), calib::CalibrationError);
  const calib::Correspondences three(s.workspace.begin(), s.workspace.begin() + 3);
  EXPECT_THROW((void)calib::calibrate_homography(three, s.camera.size()), calib::CalibrationError);
  calib::Correspondences collinear;
  for (int i = 0; i < 10; ++i) collinear.push_back({{10.0 * i, 5.0 * i}, {1.0 * i, 0.5 * i}});
  EXPECT_THROW((void)calib::calibrate_homography(collinear, s.camera.size()), calib::CalibrationError);
}

namespace {

// The full model of a simulated camera, written down from its true parameters: undistorted pixels
// to the plane z = `plane_z` of the world (where a calibration board's face would lie).
calib::Calibration true_full_model(const sim::PinholeCamera& camera, double plane_z) {
  calib::Calibration c;
  c.model = calib::Model::full;
  c.image_size = camera.size();
  c.camera_matrix = camera.camera_matrix();
  c.distortion_coefficients = camera.distortion_coefficients();
  Eigen::Matrix3d k;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) k(i, j) = c.camera_matrix.at<double>(i, j);
  }
  Eigen::Matrix3d rt;  // world (X, Y, 1) on the plane -> camera coordinates
  rt.col(0) = camera.rotation().col(0);
  rt.col(1) = camera.rotation().col(1);
  rt.col(2) = camera.rotation().col(2) * plane_z + camera.translation();
  c.image_to_world = (k * rt).inverse();
  return c;
}

}  // namespace

// A point h mm above the calibrated plane is found where its viewing ray meets that height, not
// where the plane homography would put it (the parallax of a marble's centre, of a board's face).
TEST(PlanePose, PointsAboveThePlaneAreFoundAtTheirHeight) {
  const sim::PinholeCamera camera = sim::make_global_camera({500, 500});
  for (const double plane_z : {0.0, 3.0}) {
    const calib::Calibration c = true_full_model(camera, plane_z);
    const calib::PlanePose pose = calib::plane_pose(c);
    EXPECT_NEAR(pose.x_axis.norm(), 1, 1e-9);
    EXPECT_NEAR(pose.z_axis.dot(pose.x_axis), 0, 1e-9);
    for (const double h : {0.0, 2.5, -2.5, 40.0}) {
      std::vector<Eigen::Vector2d> truth;
      std::vector<Eigen::Vector2d> pixels;
      for (const double x : {0.0, 120.0, 250.0, 499.0}) {
        for (const double y : {3.0, 250.0, 480.0}) {
          truth.emplace_back(x, y);
          pixels.push_back(*camera.project({x, y, plane_z + h}));
        }
      }
      const auto found = calib::to_world_at_height(c, pixels, h);
      const auto back = calib::to_pixel_at_height(c, truth, h);
      const auto flat = c.to_world(pixels);
      double parallax = 0;
      for (std::size_t i = 0; i < truth.size(); ++i) {
        EXPECT_LT((found[i] - truth[i]).norm(), 1e-6) << "plane " << plane_z << " height " << h << " point " << i;
        EXPECT_LT((back[i] - pixels[i]).norm(), 1e-6) << "plane " << plane_z << " height " << h << " point " << i;
        parallax = std::max(parallax, (flat[i] - truth[i]).norm());
      }
      // At the workspace's edge 1000 mm below a tilted camera, 2.5 mm of height is ~0.7 mm of parallax.
      if (h == 2.5) {
        EXPECT_GT(parallax, 0.5);
      }
    }
  }
}

TEST(PlanePose, TheHomographyModelCannotLeaveItsPlane) {
  calib::Calibration c;
  c.model = calib::Model::homography;
  const std::vector<Eigen::Vector2d> px{{10, 10}};
  EXPECT_NO_THROW((void)calib::to_world_at_height(c, px, 0));
  EXPECT_THROW((void)calib::to_world_at_height(c, px, 2.5), calib::CalibrationError);
}
