// The global camera's calibration cache: used again only under its exact key; a stale entry is
// recalibrated silently, a corrupt one with a note; a folder that cannot be written costs time only.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rig/calibration_cache.hpp"

namespace {
namespace rig = neopipe::rig;
namespace calib = neopipe::calib;

class CalibrationCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // A session that says which call made it (its calibration's reprojection error).
  rig::GlobalCameraSession made(int call) {
    rig::GlobalCameraSession s;
    calib::Calibration& c = s.calibration;
    c.model = calib::Model::full;
    c.image_size = {1280, 960};
    c.camera_matrix = (cv::Mat_<double>(3, 3) << 1744, 0, 639.5, 0, 1744, 479.5, 0, 0, 1);
    c.distortion_coefficients = (cv::Mat_<double>(1, 5) << -0.06, 0.015, 0.0004, -0.0003, 0);
    c.image_to_world(0, 2) = 12.5;
    c.report.reprojection_rms_px = call;
    c.report.held_out.sd = {0.004, 0.005};
    s.plane_height = 3;
    s.marble_height = 2.5;
    Eigen::MatrixX2d k = Eigen::MatrixX2d::Zero(6, 2);
    k(0, 0) = -0.25;
    k(4, 1) = 0.0123456789012345;
    s.bias = calib::CentroidBias(2, {1280, 960}, k);
    s.bias_held_out_px.rms = 0.02;
    s.plate_held_out_mm.rms = 0.015;
    s.plate_held_out_mm.sd = {0.01, 0.011};
    s.plate_held_out_mm.points = 144;
    s.plate_marbles = 144;
    return s;
  }

  std::filesystem::path dir_ =
      std::filesystem::path(::testing::TempDir()) / ("neopipe_calibration_cache_" + std::to_string(::getpid()));
  std::vector<std::string> notes_;
  int calls_ = 0;
  rig::CalibrationCache cache_{dir_, [this](const std::string& n) { notes_.push_back(n); }};
  std::function<rig::GlobalCameraSession()> calibrate_ = [this] { return made(++calls_); };
};

TEST_F(CalibrationCacheTest, TheSecondRunReadsWhatTheFirstStored) {
  const rig::GlobalCameraSession first = cache_.get("camera A, seed 1", calibrate_);
  EXPECT_EQ(calls_, 1);
  EXPECT_TRUE(std::filesystem::exists(cache_.file_for("camera A, seed 1")));
  const rig::GlobalCameraSession second = cache_.get("camera A, seed 1", calibrate_);
  EXPECT_EQ(calls_, 1);
  EXPECT_EQ(second.calibration.report.reprojection_rms_px, first.calibration.report.reprojection_rms_px);
  EXPECT_EQ(second.calibration.report.held_out.sd, first.calibration.report.held_out.sd);
  EXPECT_EQ(second.calibration.image_to_world, first.calibration.image_to_world);
  EXPECT_EQ(cv::norm(second.calibration.camera_matrix, first.calibration.camera_matrix), 0);
  EXPECT_EQ(second.bias.coefficients(), first.bias.coefficients());  // every digit
  EXPECT_EQ(second.bias.image_size(), first.bias.image_size());
  EXPECT_EQ(second.plane_height, 3);
  EXPECT_EQ(second.marble_height, 2.5);
  EXPECT_EQ(second.plate_held_out_mm.sd, first.plate_held_out_mm.sd);
  EXPECT_EQ(second.told_sigma(), first.told_sigma());
  EXPECT_EQ(second.plate_marbles, 144);
  EXPECT_TRUE(notes_.empty());
}

TEST_F(CalibrationCacheTest, AnotherKeyIsAnotherCalibration) {
  (void)cache_.get("camera A, seed 1", calibrate_);
  (void)cache_.get("camera A, seed 2", calibrate_);
  EXPECT_EQ(calls_, 2);
  EXPECT_NE(cache_.file_for("camera A, seed 1"), cache_.file_for("camera A, seed 2"));
}

// An entry whose file name matches but whose stored key does not (a hash collision, a file copied
// by hand, an older recipe): recalibrated and replaced without a word.
TEST_F(CalibrationCacheTest, AStaleEntryIsRecalibratedSilently) {
  (void)cache_.get("camera A, seed 1", calibrate_);
  std::filesystem::rename(cache_.file_for("camera A, seed 1"), cache_.file_for("camera B"));
  const rig::GlobalCameraSession c = cache_.get("camera B", calibrate_);
  EXPECT_EQ(calls_, 2);
  EXPECT_EQ(c.calibration.report.reprojection_rms_px, 2);
  EXPECT_TRUE(notes_.empty());
  (void)cache_.get("camera B", calibrate_);
  EXPECT_EQ(calls_, 2);  // the replacement is used
}

TEST_F(CalibrationCacheTest, ACorruptEntryIsRecalibratedWithANote) {
  for (const std::string& junk :
       {std::string("not yaml at all: [\n"), std::string("%YAML:1.0\n---\nmodel: full\n"), std::string("")}) {
    SCOPED_TRACE(junk);
    const std::string key =
        "camera C " + std::to_string(junk.rfind("neopipe_cache_key") != std::string::npos ? 9 : calls_);
    std::ofstream(cache_.file_for(key)) << junk;
    notes_.clear();
    const int before = calls_;
    (void)cache_.get(key, calibrate_);
    EXPECT_EQ(calls_, before + 1);
    ASSERT_EQ(notes_.size(), 1U);
    EXPECT_NE(notes_[0].find(cache_.file_for(key).string()), std::string::npos) << notes_[0];
    EXPECT_EQ(notes_[0].find('\n'), std::string::npos);
    (void)cache_.get(key, calibrate_);
    EXPECT_EQ(calls_, before + 1);  // rewritten whole
  }
}

TEST_F(CalibrationCacheTest, AFolderThatCannotBeWrittenOnlyCostsTime) {
  const std::filesystem::path blocked = dir_ / "file";
  std::ofstream(blocked) << "a file where the folder should be";
  const rig::CalibrationCache cache(blocked / "cache");
  (void)cache.get("k", calibrate_);
  (void)cache.get("k", calibrate_);
  EXPECT_EQ(calls_, 2);
}

}  // namespace
