// `neopipe sim world | render | video` from the command line: a rendered noiseless global frame
// run through examples/marbles.yaml gives every marble, its weighted centroid within 0.05 px RMS of
// the truth file; the same seed gives the same files; bad input is one line and a non-zero exit.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "cli_test_support.hpp"

namespace {
namespace fs = std::filesystem;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)

class SimCli : public ScratchDirTest {};

}  // namespace

TEST_F(SimCli, NoiselessGlobalFrameGivesEveryMarbleOnItsTruth) {
  const auto w = run_neopipe({"sim", "world", "--objects", "250", "--seed", "9", "--out", file("w.yaml")});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto r = run_neopipe({"sim", "render", "--realism", "ideal", "--world", file("w.yaml"), "--noise", "0", "--out",
                              file("g.png"), "--truth", file("truth.csv"), "--camera-out", file("camera.yml")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto run = run_neopipe({"run", file("g.png"), "--graph", std::string(NEOPIPE_EXAMPLES_DIR) + "/marbles.yaml",
                                "-q", "--out", file("blobs.csv")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::string th;
  std::string bh;
  const auto truth = csv_numbers(slurp(file("truth.csv")), &th);
  const auto blobs = csv_numbers(slurp(file("blobs.csv")), &bh);
  EXPECT_EQ(th, "id,u,v,u0,v0");
  ASSERT_EQ(truth.size(), 250U);
  ASSERT_EQ(blobs.size(), 250U);
  double sum2 = 0;
  for (const auto& t : truth) {
    double best = 1e9;
    for (const auto& b : blobs) best = std::min(best, std::hypot(b[9] - t[1], b[10] - t[2]));  // wcx, wcy
    sum2 += best * best;
  }
  EXPECT_LE(std::sqrt(sum2 / 250), 0.05);
  cv::FileStorage fs(file("camera.yml"), cv::FileStorage::READ);
  cv::Mat k;
  fs["camera_matrix"] >> k;
  EXPECT_EQ(k.size(), cv::Size(3, 3));
  // The homography takes the undistorted image of a marble back to its place on the workspace.
  cv::Mat h;
  cv::Mat d;
  fs["undistorted_image_to_world"] >> h;
  fs["distortion_coefficients"] >> d;
  ASSERT_EQ(h.size(), cv::Size(3, 3));
  const std::string world = slurp(file("w.yaml"));
  const auto first = world.find("  - [");
  const double x = std::stod(world.substr(first + 5));
  const double y = std::stod(world.substr(world.find(", ", first) + 2));
  std::vector<cv::Point2d> px{{truth[0][1], truth[0][2]}};
  std::vector<cv::Point2d> und;
  cv::undistortPoints(px, und, k, d, cv::noArray(), k);
  cv::Mat p = h * (cv::Mat_<double>(3, 1) << und[0].x, und[0].y, 1);
  EXPECT_NEAR(p.at<double>(0) / p.at<double>(2), x, 1e-3);
  EXPECT_NEAR(p.at<double>(1) / p.at<double>(2), y, 1e-3);
}

TEST_F(SimCli, SameSeedSameFiles) {
  for (const char* name : {"a", "b"}) {
    ASSERT_EQ(
        run_neopipe({"sim", "world", "--objects", "60", "--seed", "4", "--out", file(std::string(name) + ".yaml")})
            .exit_code,
        0);
    ASSERT_EQ(run_neopipe({"sim", "render", "--world", file(std::string(name) + ".yaml"), "--camera", "onboard",
                           "--pose", "250,250,20", "--seed", "3", "--out", file(std::string(name) + ".png")})
                  .exit_code,
              0);
  }
  EXPECT_EQ(slurp(file("a.yaml")), slurp(file("b.yaml")));
  EXPECT_EQ(cv::norm(cv::imread(file("a.png")), cv::imread(file("b.png")), cv::NORM_INF), 0);
}

TEST_F(SimCli, OnboardVideoAlongAPath) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "300", "--out", file("w.yaml")}).exit_code, 0);
  write_text(file("path.csv"), "x,y,theta\n100,100,0\n300,150,90\n");
  const auto v = run_neopipe({"sim", "video", "--world", file("w.yaml"), "--camera", "onboard", "--path",
                              file("path.csv"), "--steps", "20", "--out", file("clip.avi"), "--truth", file("t.csv")});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  cv::VideoCapture cap(file("clip.avi"));
  ASSERT_TRUE(cap.isOpened());
  EXPECT_EQ(static_cast<int>(cap.get(cv::CAP_PROP_FRAME_COUNT)), 21);
  EXPECT_EQ(static_cast<int>(cap.get(cv::CAP_PROP_FRAME_WIDTH)), 256);
  std::string header;
  (void)csv_numbers(slurp(file("t.csv")), &header);
  EXPECT_EQ(header, "frame,id,u,v,u0,v0");
  const auto g = run_neopipe({"sim", "video", "--world", file("w.yaml"), "--frames", "5", "--resolution", "320x240",
                              "--out", file("global.avi")});
  EXPECT_EQ(g.exit_code, 0) << g.err;
}

TEST_F(SimCli, BadInputIsOneLineAndNonZero) {
  write_text(file("bad.yaml"), "size: [500, 500]\nobjects:\n  - [10, 10]\n  - [11, 10]\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "render", "--world", file("bad.yaml"), "--out", file("x.png")}),
                             "bad.yaml:4:5: object 1 overlaps object 0"));
  EXPECT_TRUE(
      one_error_line(run_neopipe({"sim", "world", "--objects", "100000", "--out", file("x.yaml")}), "do not fit"));
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "10", "--out", file("w.yaml")}).exit_code, 0);
  EXPECT_TRUE(one_error_line(
      run_neopipe({"sim", "render", "--world", file("w.yaml"), "--camera", "side", "--out", file("x.png")}),
      "unknown camera"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "render", "--world", file("w.yaml"), "--camera", "onboard", "--pose",
                                          "900,10,0", "--out", file("x.png")}),
                             "outside the 500 x 500 mm workspace"));
  write_text(file("path.csv"), "x,y,theta\n100,100,0\n100,abc,0\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "video", "--world", file("w.yaml"), "--camera", "onboard", "--path",
                                          file("path.csv"), "--out", file("x.avi")}),
                             "path.csv:3: expected three numbers"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "render", "--world", file("w.yaml"), "--out", file("x.nope")}),
                             "cannot write an image"));
}
