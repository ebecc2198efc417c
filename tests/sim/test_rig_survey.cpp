// What a survey of the rig's global camera can reach: calibrate it on rendered dot-grid views (the
// project's detector, OpenCV's five-term model: the rig's lens is beyond it), find the marbles with
// the engine's blob graphs, and map their centroids to the plane of the marbles' centres (the
// calibrated plane's pose recovered from its homography; a sphere's outline is centred on the
// projection of its centre, d / 2 above the table). Under rig the calibration stays within 0.02 mm,
// but the shading pulls every centroid towards the light (more than 0.1 mm): a bias that changes
// smoothly over the workspace, so a survey that models it (here: an affine function of position)
// is left well within 0.05 mm. Mapping to the table instead of the centres' plane leaves the
// parallax (0.6 mm).

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>

#include "calib/dot_grid_detector.hpp"
#include "calib/estimate.hpp"
#include "rig_test_support.hpp"
#include "sim/target_renderer.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)
namespace calib = neopipe::calib;

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// nav_survey's calibration session: a 15 x 15 dot grid (pitch 25 mm, dots 9 mm) centred on the
// workspace, then raised and tipped.
calib::Calibration calibrate(const sim::PinholeCamera& camera, const sim::SceneRenderer& renderer) {
  const sim::CalibrationTarget grid{sim::TargetKind::dots, 15, 15, 25, 9};
  const Vector2d origin(75, 75);
  const std::vector<sim::TargetPose> poses{
      sim::target_pose(75, 75, 0, 0), sim::target_pose(80, 70, 40, 3, 20, 0), sim::target_pose(70, 80, 30, -3, 0, 22),
      sim::target_pose(80, 80, 50, 2, -15, 12), sim::target_pose(75, 70, 20, -2, 12, -15)};
  const auto plane = sim::target_points(grid);
  std::vector<calib::View> views;
  for (std::size_t v = 0; v < poses.size(); ++v) {
    const cv::Mat image = sim::render_target(grid, poses[v], camera, renderer, static_cast<std::int64_t>(v));
    const auto found = calib::find_dot_grid(image, grid.cols, grid.rows);
    EXPECT_TRUE(found) << "view " << v;
    if (!found) continue;
    calib::View view{"view " + std::to_string(v), {}};
    for (std::size_t i = 0; i < plane.size(); ++i) view.points.push_back({(*found)[i], plane[i]});
    views.push_back(std::move(view));
  }
  calib::Correspondences workspace = views.front().points;
  for (auto& p : workspace) p.world += origin;
  return calib::calibrate_full(views, workspace, camera.size());
}

// Where pixels' rays meet the plane z = h, for a calibration of the plane z = 0: its homography
// (undistorted pixels to the plane) is K [r1 r2 t] inverted, up to scale, which gives the pose.
std::vector<Vector2d> to_height(const calib::Calibration& c, const std::vector<Vector2d>& pixels, double h) {
  Eigen::Matrix3d k;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) k(i, j) = c.camera_matrix.at<double>(i, j);
  }
  const Eigen::Matrix3d m = k.inverse() * c.image_to_world.inverse();
  double scale = 2 / (m.col(0).norm() + m.col(1).norm());
  if (m(2, 2) * scale < 0) scale = -scale;  // the plane in front of the camera
  Eigen::Matrix3d r;
  r.col(0) = scale * m.col(0);
  r.col(1) = scale * m.col(1);
  r.col(2) = r.col(0).cross(r.col(1));
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  r = svd.matrixU() * svd.matrixV().transpose();  // the nearest rotation
  const Vector3d t = scale * m.col(2);
  const Vector3d centre = -r.transpose() * t;
  std::vector<cv::Point2d> px;
  px.reserve(pixels.size());
  for (const auto& p : pixels) px.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> normalised;
  cv::undistortPoints(px, normalised, c.camera_matrix, c.distortion_coefficients);
  std::vector<Vector2d> out;
  for (const auto& n : normalised) {
    const Vector3d dir = r.transpose() * Vector3d(n.x, n.y, 1);
    const Vector3d at = centre + (h - centre.z()) / dir.z() * dir;
    out.emplace_back(at.x(), at.y());
  }
  return out;
}

// Each marble's nearest mapped centroid minus its position (marbles with none within a radius left out).
std::vector<std::pair<Vector2d, Vector2d>> errors(const std::vector<Vector2d>& mapped, const sim::World& w) {
  std::vector<std::pair<Vector2d, Vector2d>> out;  // (position, error)
  for (const auto& p : w.objects) {
    Vector2d nearest(1e9, 1e9);
    for (const auto& q : mapped) {
      if ((q - p).norm() < nearest.norm()) nearest = q - p;
    }
    if (nearest.norm() < w.marble_diameter / 2) out.emplace_back(p, nearest);
  }
  return out;
}

double rms(const std::vector<std::pair<Vector2d, Vector2d>>& e) {
  double sum2 = 0;
  for (const auto& [p, d] : e) sum2 += d.squaredNorm();
  return std::sqrt(sum2 / static_cast<double>(std::max<std::size_t>(e.size(), 1)));
}

// RMS (mm) after removing the best affine function of position: what a survey that models a bias
// varying smoothly over the workspace (the shading's pull towards the light) would be left with.
double rms_after_affine(const std::vector<std::pair<Vector2d, Vector2d>>& e) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(e.size()), 3);
  Eigen::MatrixXd b(static_cast<Eigen::Index>(e.size()), 2);
  for (std::size_t i = 0; i < e.size(); ++i) {
    a.row(static_cast<Eigen::Index>(i)) << e[i].first.x(), e[i].first.y(), 1;
    b.row(static_cast<Eigen::Index>(i)) = e[i].second.transpose();
  }
  const Eigen::MatrixXd fit = a.colPivHouseholderQr().solve(b);
  return std::sqrt((b - a * fit).rowwise().squaredNorm().mean());
}

double rms_mm(const std::vector<Vector2d>& mapped, const sim::World& w, int& found) {
  const auto e = errors(mapped, w);
  found = static_cast<int>(e.size());
  return rms(e);
}

}  // namespace

TEST(RigSurvey, CalibrationHoldsAndTheShadingsPullIsASmoothBias) {
  sim::WorldRequest q;
  q.objects = 400;
  q.seed = 7;
  const sim::World w = sim::generate_world(q);
  std::printf("%-6s %-34s %8s  %8s\n", "preset", "centroid, mapped to", "RMS mm", "- affine");
  for (const auto realism : {sim::Realism::ideal, sim::Realism::rig}) {
    const sim::Rendering r = sim::rendering_for(realism, sim::CameraKind::global);
    const auto camera = sim::make_global_camera(w.size, {}, r);
    const sim::SceneRenderer renderer(r, camera);
    const calib::Calibration c = calibrate(camera, renderer);
    const cv::Mat frame = renderer.render(w.objects, w.marble_diameter, camera, 5);
    const double h = realism == sim::Realism::ideal ? 0.0 : w.marble_diameter / 2;
    std::vector<Vector2d> binary;
    for (const auto& b : blobs(frame, 60)) binary.emplace_back(b.cx, b.cy);
    std::vector<Vector2d> weighted;
    for (const auto& b : marble_blobs(frame, 60)) weighted.emplace_back(b.wcx, b.wcy);
    int found = 0;
    const double weighted_rms = rms_mm(to_height(c, weighted, h), w, found);
    EXPECT_EQ(found, 400);
    const double binary_rms = rms_mm(to_height(c, binary, h), w, found);
    EXPECT_EQ(found, 400);
    const double table_rms = rms_mm(to_height(c, weighted, 0), w, found);
    const double weighted_affine = rms_after_affine(errors(to_height(c, weighted, h), w));
    const double binary_affine = rms_after_affine(errors(to_height(c, binary, h), w));
    const std::string name = sim::realism_name(realism);
    std::printf("%-6s %-34s %8.4f  %8.4f\n", name.c_str(), "weighted (marbles.yaml), centres'", weighted_rms,
                weighted_affine);
    std::printf("%-6s %-34s %8.4f  %8.4f\n", name.c_str(), "binary (threshold 60), centres'", binary_rms,
                binary_affine);
    std::printf("%-6s %-34s %8.4f\n", name.c_str(), "weighted, table plane", table_rms);
    std::printf("%-6s calibration held-out %.4f mm RMS, reprojection %.4f px\n", name.c_str(), c.report.held_out.rms,
                c.report.reprojection_rms_px);
    EXPECT_LT(c.report.held_out.rms, 0.02) << name;
    if (realism == sim::Realism::ideal) {
      EXPECT_LT(weighted_rms, 0.01);
    } else {
      EXPECT_GT(weighted_rms, 0.1);               // the shading's pull towards the light
      EXPECT_LT(weighted_affine, 0.05);           // ... is a smooth bias
      EXPECT_GT(table_rms, 3 * weighted_affine);  // the parallax, unremoved
    }
  }
}
