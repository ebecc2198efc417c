// Calibration targets under the rig preset: a matte printed board under the same light, lens,
// vignetting, defocus and sensor as the marbles. The project's dot-grid detector finds every dot
// near its projected centre (boards lying flat, raised and tipped, and a 3 mm thick board whose face
// is at z = 3), OpenCV finds every chessboard corner; the board is lit at its own angle and has no
// highlight; under ideal it is today's image.

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "calib/dot_grid_detector.hpp"
#include "rig_test_support.hpp"
#include "sim/shading.hpp"
#include "sim/target_renderer.hpp"

using namespace rig_test;  // NOLINT(google-build-using-namespace)

namespace {

double rms_px(const std::vector<Eigen::Vector2d>& truth, const std::vector<Eigen::Vector2d>& found) {
  double sum2 = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) sum2 += (truth[i] - found[i]).squaredNorm();
  return std::sqrt(sum2 / static_cast<double>(truth.size()));
}

// The same with each truth matched to the nearest found point (OpenCV may order a board's corners
// from either end).
double rms_nearest_px(const std::vector<Eigen::Vector2d>& truth, const std::vector<Eigen::Vector2d>& found) {
  double sum2 = 0;
  for (const auto& t : truth) {
    double best = 1e9;
    for (const auto& f : found) best = std::min(best, (f - t).squaredNorm());
    sum2 += best;
  }
  return std::sqrt(sum2 / static_cast<double>(truth.size()));
}

}  // namespace

TEST(RigTargets, TheDotGridDetectorFindsEveryDot) {
  const sim::Rendering r = rig(sim::CameraKind::global);
  const auto camera = sim::make_global_camera({500, 500}, {}, r);
  const sim::SceneRenderer renderer(r, camera);
  const sim::CalibrationTarget grid{sim::TargetKind::dots, 15, 15, 25, 9};
  const std::vector<std::pair<const char*, sim::TargetPose>> poses{
      {"flat", sim::target_pose(75, 75, 0, 0)},
      {"3 mm board", sim::target_pose(75, 75, 3, 0)},  // its printed face 3 mm above the table
      {"raised, tipped", sim::target_pose(80, 70, 40, 3, 20, 0)},
      {"raised, tipped both ways", sim::target_pose(80, 80, 50, 2, -15, 12)}};
  for (std::size_t v = 0; v < poses.size(); ++v) {
    const auto& [name, pose] = poses[v];
    const cv::Mat image = sim::render_target(grid, pose, camera, renderer, static_cast<std::int64_t>(v));
    const auto found = neopipe::calib::find_dot_grid(image, grid.cols, grid.rows);
    ASSERT_TRUE(found) << name;
    const double rms = rms_px(sim::projected_target_points(grid, pose, camera), *found);
    std::printf("dot grid, %s: %zu dots, %.4f px RMS from their projected centres\n", name, found->size(), rms);
    EXPECT_LT(rms, 0.1) << name;
  }
}

TEST(RigTargets, OpenCVFindsEveryChessboardCorner) {
  const sim::Rendering r = rig(sim::CameraKind::global);
  const auto camera = sim::make_global_camera({500, 500}, {}, r);
  const sim::SceneRenderer renderer(r, camera);
  const sim::CalibrationTarget board{sim::TargetKind::chessboard, 10, 7, 25, 0};
  for (const auto& pose : {sim::target_pose(120, 150, 0, 10), sim::target_pose(140, 120, 40, -20, 25, -15)}) {
    const cv::Mat image = sim::render_target(board, pose, camera, renderer, 1);
    std::vector<cv::Point2f> corners;
    ASSERT_TRUE(cv::findChessboardCorners(image, {9, 6}, corners));
    cv::cornerSubPix(image, corners, {5, 5}, {-1, -1}, {cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4});
    std::vector<Eigen::Vector2d> found;
    found.reserve(corners.size());
    for (const auto& c : corners) found.emplace_back(c.x, c.y);
    ASSERT_EQ(found.size(), 54U);
    const double rms = rms_nearest_px(sim::projected_target_points(board, pose, camera), found);
    std::printf("chessboard: %.4f px RMS from the projected corners\n", rms);
    EXPECT_LT(rms, 0.15);
  }
}

TEST(RigTargets, TheBoardIsMatteAndLitAtItsOwnAngle) {
  // A board of white paper: each pixel's light is the paper's albedo times the light it gets,
  // nothing more (no highlight), and tipping the board away from the light darkens it.
  sim::Rendering r = quiet(rig(sim::CameraKind::global));
  const auto camera = sim::make_global_camera({500, 500}, {}, r);
  const sim::SceneRenderer renderer(r, camera);
  const sim::CalibrationTarget paper{sim::TargetKind::chessboard, 2, 2, 100, 0};  // one inner corner
  const sim::Shader shader(*r.light, r.light->position, r.light->position.z());
  const auto paper_light = [&](const sim::TargetPose& pose) {
    const cv::Mat light = sim::target_light(paper, pose, camera, renderer);
    // The white square at target (50..100, -100..-50) mm: sample its middle.
    const Eigen::Vector3d at = pose.rotation * Eigen::Vector3d(75, -75, 0) + pose.translation;
    const auto px = *camera.project(at);
    const double expected = r.surfaces.marble * shader.lit(shader.direct(at, pose.rotation.col(2)));
    return std::pair{static_cast<double>(
                         light.at<float>(static_cast<int>(std::lround(px.y())), static_cast<int>(std::lround(px.x())))),
                     expected};
  };
  const auto [flat, flat_expected] = paper_light(sim::target_pose(200, 300, 0, 0));
  // The light hangs above the north-west corner: a face turned 40 degrees East looks away from it.
  const auto [tipped, tipped_expected] = paper_light(sim::target_pose(200, 300, 30, 0, 0, 40));
  std::printf("white paper: flat %.2f (expected %.2f), tipped away from the light %.2f (expected %.2f)\n", flat,
              flat_expected, tipped, tipped_expected);
  EXPECT_NEAR(flat, flat_expected, 0.05);
  EXPECT_NEAR(tipped, tipped_expected, 0.05);
  EXPECT_LT(tipped, flat - 10);
  EXPECT_LE(flat, r.surfaces.marble);
}
