// The camera model against OpenCV: projection with distortion equals cv::projectPoints, pixels map
// back to the plane, the global camera sees the whole workspace through a true projective map, and
// the onboard window has side a with the tool's axes as image right and up.

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "sim/cameras.hpp"

namespace sim = neopipe::sim;

TEST(Camera, ProjectionEqualsOpenCVProjectPoints) {
  const sim::PinholeCamera cam = sim::make_global_camera({500, 500});
  std::vector<cv::Point3d> world;
  for (double x = 0; x <= 500; x += 50) {
    for (double y = 0; y <= 500; y += 50) world.emplace_back(x, y, 0);
  }
  world.emplace_back(100, 200, 30);  // off the plane too
  cv::Mat r(3, 3, CV_64F);
  cv::Mat t(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.at<double>(i, j) = cam.rotation()(i, j);
    t.at<double>(i) = cam.translation()(i);
  }
  cv::Mat rvec;
  cv::Rodrigues(r, rvec);
  std::vector<cv::Point2d> expected;
  cv::projectPoints(world, rvec, t, cam.camera_matrix(), cam.distortion_coefficients(), expected);
  for (std::size_t i = 0; i < world.size(); ++i) {
    const auto p = cam.project({world[i].x, world[i].y, world[i].z});
    ASSERT_TRUE(p);
    EXPECT_NEAR(p->x(), expected[i].x, 1e-8);
    EXPECT_NEAR(p->y(), expected[i].y, 1e-8);
  }
}

TEST(Camera, PixelsMapBackToThePlane) {
  const sim::PinholeCamera cam = sim::make_global_camera({500, 500});
  for (double x = 5; x < 500; x += 37) {
    for (double y = 5; y < 500; y += 41) {
      const auto px = cam.project({x, y, 0});
      ASSERT_TRUE(px);
      const auto back = cam.plane_point(*px);
      ASSERT_TRUE(back);
      EXPECT_NEAR(back->x(), x, 1e-9);
      EXPECT_NEAR(back->y(), y, 1e-9);
    }
  }
}

TEST(Camera, GlobalCameraSeesTheWholeWorkspaceThroughAProjectiveMap) {
  const sim::PinholeCamera cam = sim::make_global_camera({500, 500});
  std::vector<cv::Point2d> image;
  std::vector<cv::Point2d> plane;
  for (const double x : {0.0, 500.0}) {
    for (const double y : {0.0, 500.0}) {
      const auto p = cam.project({x, y, 0});
      ASSERT_TRUE(p);
      EXPECT_GT(p->x(), 0);
      EXPECT_GT(p->y(), 0);
      EXPECT_LT(p->x(), 1279);
      EXPECT_LT(p->y(), 959);
    }
  }
  // North is up: y grows, v falls.
  EXPECT_LT(cam.project({250, 400, 0})->y(), cam.project({250, 100, 0})->y());
  // Not a scale: opposite workspace edges have different lengths in the image (tilt).
  const double south = (*cam.project({500, 0, 0}) - *cam.project({0, 0, 0})).norm();
  const double north = (*cam.project({500, 500, 0}) - *cam.project({0, 500, 0})).norm();
  EXPECT_GT(std::abs(south - north), 5.0);
}

TEST(Camera, OnboardWindowFollowsTheToolFrame) {
  const sim::OnboardCameraConfig config;                  // 256 px over 50 mm
  const sim::Pose2 pose{200, 300, std::numbers::pi / 2};  // tool x points North
  const sim::PinholeCamera cam = sim::make_onboard_camera(pose, config);
  const auto centre = cam.project({200, 300, 0});
  EXPECT_NEAR(centre->x(), 127.5, 1e-9);
  EXPECT_NEAR(centre->y(), 127.5, 1e-9);
  // 10 mm along the tool's x (North) is 51.2 px to the right.
  const auto ahead = cam.project({200, 310, 0});
  EXPECT_NEAR(ahead->x(), 127.5 + 51.2, 1e-9);
  EXPECT_NEAR(ahead->y(), 127.5, 1e-9);
  // 10 mm along the tool's y (West) is 51.2 px up.
  const auto left = cam.project({190, 300, 0});
  EXPECT_NEAR(left->x(), 127.5, 1e-9);
  EXPECT_NEAR(left->y(), 127.5 - 51.2, 1e-9);
}
