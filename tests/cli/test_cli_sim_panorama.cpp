// `neopipe sim panorama` from the command line: the JSON readings of marbles at known places (one
// across the ring's seam), the compass, the false-colour picture, --help, and bad input (a position
// off the table or inside a marble, an unreadable world, a malformed --at) as one line and a
// non-zero exit.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cli_test_support.hpp"

namespace {
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

class SimPanoramaCli : public ScratchDirTest {
 protected:
  // Marble 0 50 mm east of (250, 250), marble 1 100 mm north of it.
  std::string world() {
    write_text(file("w.yaml"), "size: [500, 500]\nobjects:\n  - [300, 250]\n  - [250, 350]\n");
    return file("w.yaml");
  }
};

double angle_diff(double a, double b) {
  return std::fmod(a - b + 540.0, 360.0) - 180.0;
}

TEST_F(SimPanoramaCli, JsonReadingsCompassAndPicture) {
  const auto r =
      run_neopipe({"sim", "panorama", "--world", world(), "--at", "250,250,90", "--json", "--out", file("ring.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j.at("readings").size(), 2U);
  // Facing north: marble 0 (east) lies at 270°, marble 1 (north) straight ahead, across the seam.
  const double truth_bearing[] = {270, 0};
  const double truth_range[] = {50, 100};
  for (const auto& reading : j.at("readings")) {
    const int id = reading.at("id").get<int>();
    ASSERT_TRUE(id == 0 || id == 1);
    EXPECT_LT(std::abs(angle_diff(reading.at("bearing_deg").get<double>(), truth_bearing[id])), 0.2);
    const auto range = reading.at("range_mm");
    EXPECT_LE(range.at(0).get<double>(), truth_range[id]);
    EXPECT_GE(range.at(1).get<double>(), truth_range[id]);
    EXPECT_GT(reading.at("area_px").get<int>(), 20);
  }
  EXPECT_EQ(j.at("compass").at("sigma_deg").get<double>(), 1.0);
  EXPECT_LT(std::abs(angle_diff(j.at("compass").at("heading_deg").get<double>(), 90)), 6.0);
  const cv::Mat png = cv::imread(file("ring.png"), cv::IMREAD_COLOR);
  ASSERT_EQ(png.size(), cv::Size(3600, 320));
  EXPECT_NE(png.at<cv::Vec3b>(160, 2699), cv::Vec3b(0, 0, 0));  // marble 0's disc
  EXPECT_NE(png.at<cv::Vec3b>(160, 0), cv::Vec3b(0, 0, 0));     // marble 1's, at the seam
  EXPECT_EQ(png.at<cv::Vec3b>(160, 1800), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(png.at<cv::Vec3b>(10, 2699), cv::Vec3b(0, 0, 0));
}

TEST_F(SimPanoramaCli, CsvWithoutJsonAndTheSameSeedTheSameReadings) {
  const auto a = run_neopipe({"sim", "panorama", "--world", world(), "--at", "200,200", "--noise", "0.5"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out.rfind("id,bearing_deg,range_lo_mm,range_hi_mm,area_px,partial\n", 0), 0U);
  EXPECT_EQ(std::count(a.out.begin(), a.out.end(), '\n'), 3);
  EXPECT_EQ(run_neopipe({"sim", "panorama", "--world", world(), "--at", "200,200", "--noise", "0.5"}).out, a.out);
  EXPECT_NE(
      run_neopipe({"sim", "panorama", "--world", world(), "--at", "200,200", "--noise", "0.5", "--seed", "2"}).out,
      a.out);
}

TEST_F(SimPanoramaCli, HelpNamesItsOptions) {
  const auto r = run_neopipe({"sim", "panorama", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* o : {"--world", "--at", "--out", "--json", "--noise", "--range", "--seed"}) {
    EXPECT_NE(r.out.find(o), std::string::npos) << o;
  }
}

TEST_F(SimPanoramaCli, BadInputIsOneLineAndNonZero) {
  const std::string w = world();
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "600,10"}),
                             "outside the 500 x 500 mm table"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "301,250"}), "inside marble 0"));
  EXPECT_TRUE(
      one_error_line(run_neopipe({"sim", "panorama", "--world", file("none.yaml"), "--at", "1,1"}), "none.yaml"));
  write_text(file("bad.yaml"), "size: [500, 500]\nobjects: [[1, 2, 3\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", file("bad.yaml"), "--at", "1,1"}), "bad.yaml"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "1,x"}), "expected X,Y"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "1,2,3,4"}), "expected X,Y"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w}), "--at"));
  EXPECT_TRUE(
      one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "1,1", "--noise", "-1"}), "--noise"));
  EXPECT_TRUE(one_error_line(run_neopipe({"sim", "panorama", "--world", w, "--at", "1,1", "--out", file("x.nope")}),
                             "cannot write an image"));
}

}  // namespace
