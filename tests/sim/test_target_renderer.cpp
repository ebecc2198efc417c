// Calibration targets against OpenCV: cv::findChessboardCorners + cornerSubPix finds every inner
// corner of a rendered chessboard (flat on the workspace and tilted) near its projected truth, and
// the blob extractor finds every dot of a dot grid near its projected centre.

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "kernels/blobs.hpp"
#include "sim/cameras.hpp"
#include "sim/target_renderer.hpp"

namespace sim = neopipe::sim;

namespace {

// RMS distance from each truth point to the nearest found point; -1 when counts differ.
double rms_nearest(const std::vector<Eigen::Vector2d>& truth, const std::vector<cv::Point2d>& found) {
  if (truth.size() != found.size()) return -1;
  double sum2 = 0;
  for (const auto& t : truth) {
    double best = 1e9;
    for (const auto& f : found) best = std::min(best, std::hypot(f.x - t.x(), f.y - t.y()));
    sum2 += best * best;
  }
  return std::sqrt(sum2 / static_cast<double>(truth.size()));
}

double chessboard_rms(const sim::TargetPose& pose) {
  const sim::CalibrationTarget board{sim::TargetKind::chessboard, 10, 7, 25, 0};
  const auto camera = sim::make_global_camera({500, 500});
  const sim::MarbleRenderer renderer(sim::ImageModel{}, camera.size());
  const cv::Mat img = sim::render_target(board, pose, camera, renderer);
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(img, {9, 6}, corners)) return -1;
  cv::cornerSubPix(img, corners, {5, 5}, {-1, -1}, {cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4});
  std::vector<cv::Point2d> found(corners.begin(), corners.end());
  return rms_nearest(sim::projected_target_points(board, pose, camera), found);
}

}  // namespace

TEST(TargetRenderer, ChessboardCornersAreWhereOpenCVFindsThem) {
  const double flat = chessboard_rms(sim::target_pose(120, 150, 0, 10));
  const double tilted = chessboard_rms(sim::target_pose(140, 120, 40, -20, 25, -15));
  std::printf("chessboard corners vs truth: flat %.4f px, tilted %.4f px RMS\n", flat, tilted);
  EXPECT_GE(flat, 0);
  EXPECT_LT(flat, 0.1);
  EXPECT_GE(tilted, 0);
  EXPECT_LT(tilted, 0.1);
}

TEST(TargetRenderer, DotCentroidsAreOnTheProjectedCentres) {
  const sim::CalibrationTarget grid{sim::TargetKind::dots, 11, 8, 30, 10};
  const auto camera = sim::make_global_camera({500, 500});
  sim::ImageModel model;
  model.noise_sigma = 0;
  const sim::MarbleRenderer renderer(model, camera.size());
  const auto pose = sim::target_pose(100, 120, 0, 5);
  const cv::Mat img = sim::render_target(grid, pose, camera, renderer);
  // Excess over a level between board and dots, as examples/marbles.yaml weighs marbles.
  cv::Mat excess;
  cv::subtract(img, cv::Scalar(100), excess);
  neopipe::kernels::BlobParams params;
  params.threshold = 0;
  const auto blobs = neopipe::kernels::extract_blobs(excess, params, excess);
  std::vector<cv::Point2d> found;
  for (const auto& b : blobs) found.emplace_back(b.wcx, b.wcy);
  const double rms = rms_nearest(sim::projected_target_points(grid, pose, camera), found);
  std::printf("dot centroids vs projected centres: %.4f px RMS\n", rms);
  EXPECT_GE(rms, 0);
  EXPECT_LT(rms, 0.05);
}
