// Replays, in the normal build, the inputs that made a fuzz target (fuzz/) crash: each goes through
// the same entry point as in its target and must end in the reader's documented error (or read
// cleanly), never in a crash or another exception. The inputs are under tests/data/fuzz/<target>/;
// a new one needs only its file there: the "Every...Replays" tests read whole folders. Under
// -DNEOPIPE_SANITIZE=address,undefined these tests also catch what only a sanitizer sees.
// docs/reliability.md lists the findings.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "calib/calibration.hpp"
#include "calib/points_csv.hpp"
#include "nav/common/custom_map.hpp"
#include "nav/mapmaker/workspace.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/io/image_signature.hpp"
#include "pipeline/io/libav_video_source.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/source_location.hpp"
#include "sim/arm/moves_csv.hpp"
#include "sim/world.hpp"

namespace neopipe {
namespace {

namespace fs = std::filesystem;
namespace pl = pipeline;

const fs::path kData = fs::path(NEOPIPE_FUZZ_DATA_DIR);

std::vector<fs::path> reproducers(const std::string& target) {
  std::vector<fs::path> files;
  if (fs::is_directory(kData / target)) {
    for (const auto& e : fs::directory_iterator(kData / target)) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string text_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What each fuzz target does with an input: the documented error's message, or "" when the input
// reads cleanly. Any other exception escapes, and fails the test that replays it.

std::string replay_graph_spec(const fs::path& file) {
  try {
    const pl::GraphSpec spec = pl::parse_graph_spec(text_of(file), file.string());
    pl::InlineRunner runner(pl::compile(spec, pl::standard_kernels()));
    cv::Mat frame(13, 21, runner.graph().source_type() == pl::PortType::bgr8 ? CV_8UC3 : CV_8UC1);
    cv::randu(frame, 0, 256);
    runner.run(frame);
    runner.run(frame);
  } catch (const pl::GraphError& e) {
    return e.what();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string replay_world(const fs::path& file) {
  try {
    (void)sim::load_world(file.string());
  } catch (const sim::WorldError& e) {
    return e.what();
  }
  return "";
}

std::string replay_calibration(const fs::path& file) {
  try {
    const calib::Calibration c = calib::load_calibration(file.string());
    (void)c.to_world({{0, 0}, {320, 240}});
    (void)c.to_pixel({{0, 0}, {100, 100}});
  } catch (const calib::CalibrationError& e) {
    return e.what();
  }
  return "";
}

std::string replay_moves_csv(const fs::path& file) {
  try {
    sim::MovesReader reader(file.string());
    while (reader.next()) {
    }
  } catch (const sim::MovesError& e) {
    return e.what();
  }
  return "";
}

std::string replay_points_csv(const fs::path& file) {
  try {
    (void)calib::read_points_csv(file.string());
  } catch (const calib::CalibrationError& e) {
    return e.what();
  }
  return "";
}

std::string replay_blob_table(const fs::path& file) {
  namespace mm = nav::mapmaker;
  try {
    mm::check_workspace(mm::Workspace{{500, 500}, mm::read_blob_positions(file.string())}, file.string());
  } catch (const mm::MapError& e) {
    return e.what();
  }
  return "";
}

std::string replay_custom_map(const fs::path& file) {
  try {
    const nav::CustomMap map = nav::parse_custom_map(text_of(file));
    EXPECT_EQ(nav::parse_custom_map(nav::format_custom_map(map)), map) << file;
  } catch (const nav::CustomMapError& e) {
    return e.what();
  }
  return "";
}

std::string replay_image_signature(const fs::path& file) {
  const std::string head = text_of(file).substr(0, 132);
  EXPECT_EQ(pipeline::io::has_image_signature(head), pipeline::io::file_has_image_signature(file.string())) << file;
  return "";
}

// Both colour formats, as the fuzz target picks one by the input's length; every frame.
std::string replay_video(const fs::path& file) {
  namespace io = pipeline::io;
  std::string errors;
  for (const io::ColorFormat format : {io::ColorFormat::gray, io::ColorFormat::bgr}) {
    try {
      io::LibavVideoSource video(file.string(), format);
      while (video.next()) {
      }
    } catch (const io::SourceError& e) {
      errors += e.what();
    }
  }
  return errors;
}

void replay_all(const std::string& target, const std::function<std::string(const fs::path&)>& replay) {
  for (const fs::path& file : reproducers(target)) {
    SCOPED_TRACE(file.string());
    EXPECT_NO_THROW((void)replay(file));
  }
}

TEST(FuzzRegressions, EveryGraphSpecReplays) {
  replay_all("graph_spec", replay_graph_spec);
}
TEST(FuzzRegressions, EveryWorldReplays) {
  replay_all("world", replay_world);
}
TEST(FuzzRegressions, EveryCalibrationReplays) {
  replay_all("calibration", replay_calibration);
}
TEST(FuzzRegressions, EveryMovesCsvReplays) {
  replay_all("moves_csv", replay_moves_csv);
}
TEST(FuzzRegressions, EveryPointsCsvReplays) {
  replay_all("points_csv", replay_points_csv);
}
TEST(FuzzRegressions, EveryBlobTableReplays) {
  replay_all("blob_table", replay_blob_table);
}
TEST(FuzzRegressions, EveryCustomMapReplays) {
  replay_all("custom_map", replay_custom_map);
}
TEST(FuzzRegressions, EveryImageSignatureReplays) {
  replay_all("image_signature", replay_image_signature);
}
TEST(FuzzRegressions, EveryVideoReplays) {
  replay_all("video", replay_video);
}

// The findings one by one, with the error each must now give.

// yaml-cpp's own TypedBadConversion escaped for a key that is a map or a list.
TEST(FuzzRegressions, AGraphSpecKeyThatIsNotANameIsAGraphError) {
  const std::string error = replay_graph_spec(kData / "graph_spec/list-as-key.yaml");
  EXPECT_NE(error.find(":3:34: a key must be a single name"), std::string::npos) << error;
}

TEST(FuzzRegressions, AWorldKeyThatIsNotANameIsAWorldError) {
  const std::string error = replay_world(kData / "world/list-as-key.yaml");
  EXPECT_NE(error.find("list-as-key.yaml:1:1: a key must be a single name"), std::string::npos) << error;
}

// The overlap check's grid had a cell per marble diameter whatever the workspace's size: 2e59 mm
// asked for more cells than an int holds (UBSan) and than memory. Its cells are coarser there now.
TEST(FuzzRegressions, AWorldFarLargerThanItsMarblesLoads) {
  EXPECT_EQ(replay_world(kData / "world/huge-size.yaml"), "");
  sim::World w;
  w.size = {2e59, 100};
  w.objects = {{10, 50}, {1e59, 50}};
  EXPECT_FALSE(sim::first_overlap(w, 0.0));
  w.objects.emplace_back(12, 50);  // 2 mm from the first: the coarse grid must still see it
  ASSERT_TRUE(sim::first_overlap(w, 0.0));
  EXPECT_EQ(*sim::first_overlap(w, 0.0), (std::pair<std::size_t, std::size_t>{0, 2}));
}

// The calibration reader went through cv::FileStorage, whose exceptions (other than at open) were not
// caught; and OpenCV 4.6's readers hang, crash or over-allocate on some files. It reads with
// yaml-cpp now (calib/calibration.cpp says why); each file below must give a CalibrationError.
std::string calibration_error(const std::string& name) {
  return replay_calibration(kData / "calibration" / name);
}

TEST(FuzzRegressions, CalibrationMatrixDataThatAreNotNumbersAreACalibrationError) {
  const std::string error = calibration_error("matrix-data-not-numbers.yaml");
  EXPECT_NE(error.find("malformed 'camera_matrix' (data element 0 is not a number)"), std::string::npos) << error;
}

// 'cols' was read as INT_MAX, and 16 GiB allocated for it.
TEST(FuzzRegressions, ACalibrationMatrixSizeThatIsNotANumberIsACalibrationError) {
  EXPECT_NE(calibration_error("size-not-a-number.yaml").find("not a calibration file"), std::string::npos);
}

// OpenCV let std::length_error out (after reading a byte before its buffer).
TEST(FuzzRegressions, ACalibrationKeyWithNothingBeforeItsColonIsACalibrationError) {
  EXPECT_NE(calibration_error("empty-key.yaml").find("not a calibration file"), std::string::npos);
}

// OpenCV's XML reader (it reads XML whatever the file's name) dereferenced a null pointer.
TEST(FuzzRegressions, AnXmlCalibrationFileIsACalibrationError) {
  EXPECT_NE(calibration_error("xml-null-dereference.yaml").find("not a calibration file"), std::string::npos);
}

// OpenCV's YAML reader never returned from these (a ctest timeout would say so); the second got
// past a check that yaml-cpp sees a map before OpenCV reads the file, the first attempt at a fix.
TEST(FuzzRegressions, CalibrationFilesThatHungOpenCVAreCalibrationErrors) {
  EXPECT_NE(calibration_error("opencv-yaml-hang.yaml").find("not a calibration file"), std::string::npos);
  EXPECT_NE(calibration_error("opencv-yaml-hang-2.yaml").find("malformed 'model'"), std::string::npos);
}

// yaml-cpp 0.7's LoadAll loops for ever on a stray ','; the reader loads one document only.
TEST(FuzzRegressions, ACalibrationFileWithAStrayCommaIsACalibrationError) {
  EXPECT_NE(calibration_error("stray-comma.yaml").find("not a calibration file"), std::string::npos);
}

// The reproducer is a damaged MP4 whose display matrix is all zeros: the reader took NaN for its
// angle at open, before decoding (only UBSan saw it: a negated INT_MIN). No frame of it decodes.
TEST(FuzzRegressions, AVideoWithADegenerateDisplayMatrixIsASourceError) {
  const std::string error = replay_video(kData / "video/degenerate-display-matrix.mp4");
  EXPECT_NE(error.find("degenerate-display-matrix.mp4: the video has no frames"), std::string::npos) << error;
}

}  // namespace
}  // namespace neopipe
