// `neopipe sim world | render | video` from the command line: a rendered noiseless global frame
// (ideal realism) run through examples/marbles.yaml gives every marble, its weighted centroid within
// 0.05 px RMS of the truth file; rig is the default, its truth has the parallax, each effect option
// changes the image, --help names them all; the same seed gives the same files; bad input is one
// line and a non-zero exit.

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

TEST_F(SimCli, RigIsTheDefaultAndItsTruthHasTheParallax) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "80", "--seed", "2", "--out", file("w.yaml")}).exit_code, 0);
  const auto r = run_neopipe({"sim", "render", "--world", file("w.yaml"), "--out", file("rig.png"), "--truth",
                              file("t.csv"), "--camera-out", file("camera.yml")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("rig realism"), std::string::npos) << r.err;
  std::string header;
  const auto truth = csv_numbers(slurp(file("t.csv")), &header);
  EXPECT_EQ(header, "id,u,v,u0,v0");
  ASSERT_EQ(truth.size(), 80U);
  for (const auto& t : truth) EXPECT_GT(std::hypot(t[1] - t[3], t[2] - t[4]), 0.01);  // centre above contact point
  // The same with --realism rig given: the same file; ideal: another image.
  ASSERT_EQ(run_neopipe({"sim", "render", "--world", file("w.yaml"), "--realism", "rig", "--out", file("rig2.png")})
                .exit_code,
            0);
  EXPECT_EQ(slurp(file("rig.png")), slurp(file("rig2.png")));
  ASSERT_EQ(
      run_neopipe({"sim", "render", "--world", file("w.yaml"), "--realism", "ideal", "--out", file("i.png")}).exit_code,
      0);
  EXPECT_GT(cv::norm(cv::imread(file("rig.png")), cv::imread(file("i.png")), cv::NORM_INF), 0);
  // The camera file says what the lens was beyond OpenCV's five terms.
  cv::FileStorage fs(file("camera.yml"), cv::FileStorage::READ);
  cv::Mat extra;
  fs["extra_distortion_coefficients"] >> extra;
  ASSERT_EQ(extra.size(), cv::Size(5, 1));
  EXPECT_GT(cv::norm(extra), 0);
}

TEST_F(SimCli, EffectOptionsOverrideThePreset) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "300", "--seed", "2", "--out", file("w.yaml")}).exit_code, 0);
  const std::vector<std::string> base{"sim",      "render",  "--world", file("w.yaml"),
                                      "--camera", "onboard", "--pose",  "250,250,10"};
  const auto render = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"--out", file(name)});
    const auto r = run_neopipe(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return cv::imread(file(name), cv::IMREAD_GRAYSCALE);
  };
  const cv::Mat rig = render("rig.png", {});
  for (const auto& option : std::vector<std::vector<std::string>>{{"--no-light"},
                                                                  {"--light", "500,0,800"},
                                                                  {"--no-shadows"},
                                                                  {"--texture", "0"},
                                                                  {"--vignetting", "0"},
                                                                  {"--defocus", "2"},
                                                                  {"--full-well", "2000"},
                                                                  {"--prnu", "0.05"},
                                                                  {"--noise", "5"},
                                                                  {"--lens-extra", "0,0.01"},
                                                                  {"--distortion", "-0.05"},
                                                                  {"--specular", "0"}}) {
    EXPECT_GT(cv::norm(render("x.png", option), rig, cv::NORM_INF), 0) << option.front();
  }
  // Everything off but the geometry: a noiseless frame, the same twice.
  const std::vector<std::string> still{"--no-light",      "--texture", "0", "--vignetting", "0", "--noise", "0",
                                       "--no-shot-noise", "--prnu",    "0"};
  const cv::Mat a = render("a.png", still);
  EXPECT_EQ(cv::norm(a, render("b.png", still), cv::NORM_INF), 0);
  cv::Mat table = a(cv::Rect(0, 0, 20, 20));
  double lo = 0;
  double hi = 0;
  cv::minMaxLoc(table, &lo, &hi);
  EXPECT_LE(hi - lo, 1);  // no noise, no texture, no light: a flat table
}

TEST_F(SimCli, VideoRealismInterlaceAndCodec) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "1000", "--seed", "3", "--out", file("w.yaml")}).exit_code, 0);
  write_text(file("path.csv"), "x,y,theta\n100,100,0\n160,100,0\n");
  const auto harsh = run_neopipe({"sim", "video", "--world", file("w.yaml"), "--camera", "onboard", "--path",
                                  file("path.csv"), "--steps", "4", "--realism", "harsh", "--codec", "none", "--out",
                                  file("harsh.avi"), "--truth", file("t.csv"), "-q"});
  ASSERT_EQ(harsh.exit_code, 0) << harsh.err;
  EXPECT_NE(harsh.err.find("harsh realism"), std::string::npos);
  EXPECT_NE(harsh.err.find("codec none"), std::string::npos);
  std::string header;
  (void)csv_numbers(slurp(file("t.csv")), &header);
  EXPECT_EQ(header, "frame,id,u,v,u0,v0");
  const auto jpeg =
      run_neopipe({"sim", "video", "--world", file("w.yaml"), "--camera", "onboard", "--path", file("path.csv"),
                   "--steps", "4", "--codec", "jpeg", "--quality", "30", "--out", file("rig.avi"), "-q"});
  ASSERT_EQ(jpeg.exit_code, 0) << jpeg.err;
  EXPECT_NE(jpeg.err.find("codec jpeg 30"), std::string::npos) << jpeg.err;
  cv::VideoCapture cap(file("rig.avi"));
  ASSERT_TRUE(cap.isOpened());
  EXPECT_EQ(static_cast<int>(cap.get(cv::CAP_PROP_FRAME_COUNT)), 5);
}

TEST_F(SimCli, HelpNamesEveryRealismOption) {
  const auto render = run_neopipe({"sim", "render", "--help"});
  const auto video = run_neopipe({"sim", "video", "--help"});
  for (const char* option :
       {"--realism",    "--light",     "--no-light",     "--ambient",    "--specular",      "--shininess",
        "--no-shadows", "--texture",   "--distortion",   "--lens-extra", "--vignetting",    "--blur",
        "--defocus",    "--noise",     "--read-noise",   "--full-well",  "--no-shot-noise", "--prnu",
        "--gradient",   "--interlace", "--no-interlace", "--seed"}) {
    EXPECT_NE(render.out.find(option), std::string::npos) << option;
    EXPECT_NE(video.out.find(option), std::string::npos) << option;
  }
  EXPECT_NE(video.out.find("--codec"), std::string::npos);
  EXPECT_NE(video.out.find("--quality"), std::string::npos);
}

TEST_F(SimCli, BadRealismInputIsOneLineAndNonZero) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "10", "--out", file("w.yaml")}).exit_code, 0);
  const auto bad = [&](std::vector<std::string> options, const std::string& says) {
    std::vector<std::string> args{"sim", "render", "--world", file("w.yaml"), "--out", file("x.png")};
    args.insert(args.end(), options.begin(), options.end());
    EXPECT_TRUE(one_error_line(run_neopipe(args), says)) << options.front();
  };
  bad({"--realism", "real"}, "--realism");
  bad({"--full-well", "0"}, "--full-well (sensor.full_well: must be > 0 electrons (got 0))");
  bad({"--noise", "-1"}, "--noise (sensor.read_noise: must be 0 .. 64 gray levels (got -1))");
  bad({"--light", "10,10"}, "--light '10,10': expected x,y,z (mm)");
  bad({"--light", "10,10,-5"}, "z = -5 mm is at or below the table");
  bad({"--light", "10,10,3"}, "not above the marbles' tops");
  bad({"--no-light", "--ambient", "0.5"}, "need a light");
  bad({"--light", "1,2,900", "--no-light"}, "--light and --no-light: choose one");
  bad({"--interlace", "--no-interlace"}, "choose one");
  bad({"--texture", "2"}, "--texture (surfaces.texture: must be in [0, 1)");
  bad({"--prnu", "0.7"}, "--prnu");
  bad({"--vignetting", "1"}, "--vignetting");
  bad({"--defocus", "20"}, "--defocus");
  bad({"--lens-extra", "1,2,3,4,5,6"}, "--lens-extra '1,2,3,4,5,6': expected up to five numbers k4,s1,s2,s3,s4");
  bad({"--distortion", "-3"}, "folds the image");
  write_text(file("path.csv"), "x,y,theta\n100,100,0\n110,100,0\n");
  EXPECT_TRUE(
      one_error_line(run_neopipe({"sim", "video", "--world", file("w.yaml"), "--camera", "onboard", "--path",
                                  file("path.csv"), "--codec", "none", "--quality", "50", "--out", file("x.avi")}),
                     "--quality is for --codec jpeg"));
}
