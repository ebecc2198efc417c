// Tests of the FFmpeg video reader (pipeline/io/libav_video_source.hpp) against cv::VideoCapture,
// the reader it replaces, on real videos: OpenCV's sample vtest.avi (MS-MPEG-4, 768x576, from
// Debian's opencv-doc) and videos made here with cv::VideoWriter and the ffmpeg tool in the pixel
// formats decoders hand out: mpeg4 yuv420p (limited range), MJPG yuvj420p (full range), FFV1
// yuv420p / yuv422p / yuv444p and raw nv12 and gray, several at an odd size (333x201) so that the
// planes' rows are padded.
//
// Checked, frame by frame in lockstep with cv::VideoCapture: the same number of frames in the same
// order, fps and frame count; BGR frames identical; gray frames (the decoder's luma plane, expanded
// from limited range) against cv::cvtColor(BGR2GRAY) of cv::VideoCapture's BGR within measured
// tolerances (see Tolerance). Also: a full-range flag on yuv420p is honoured (where the reader
// parts from cv::VideoCapture on purpose), a display matrix turns the frames, every frame is
// freshly allocated, the decoder thread count; a truncated video and a text file named .mp4 are
// SourceErrors naming the file.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/libav_video_source.hpp"
#include "pipeline_test_support.hpp"

namespace io = neopipe::pipeline::io;
namespace fs = std::filesystem;
using neopipe::pipeline::testing::same_image;
using neopipe::pipeline::testing::TempDir;

namespace {

const std::string kVtest = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";

// Gray from the luma plane against BT.601 gray of cv::VideoCapture's BGR. They differ for two
// reasons, both on swscale's side: (1) its fixed-point YUV -> BGR truncates rather than rounds (a
// flat limited-range gray Y = 32 gives BGR 18, 18, 18 where 255 * 16 / 219 = 18.6), so its gray is
// low by 0.5 to 2 levels on most pixels of colourful video; (2) colours outside what BGR can hold,
// at sharp colour edges (chroma shared by 2x2 pixels, or a scaler's ringing), are clipped to 0..255
// before cvtColor weighs them, which moves their gray by up to tens of levels on those edge pixels.
// The luma path computes round((Y - 16) * 255 / 219) exactly. Measured, max / mean absolute
// difference / share of pixels within 2 levels, over all frames:
//   vtest.avi                         24 / 1.22 / 0.993
//   mpeg4, smooth random colours       3 / 1.29 / 0.999
//   MJPG (full range)                  2 / 0.82 / 1.000
//   testsrc2 scaled to 333x201 in FFV1 yuv420p, yuv422p, yuv444p, raw nv12, MJPEG yuvj420p
//                                27-32 / 0.38-0.49 / 0.950-0.956 (5 % of the pixels lie on bar edges)
//   raw gray and yuyv422 (through BGR)  0 / 0 / 1
// The tolerances leave some room above those. Taking limited-range video for full range (no
// expansion) fails them: mean 6.0 and 20 % within 2 on vtest.avi, mean 7.8 and 17 % on testsrc2,
// max 7 and 94 % within 2 on the smooth mpeg4.
struct Tolerance {
  int max_abs;
  double mean_abs;
  double within_2;  ///< least share of pixels within 2 gray levels
};

struct Comparison {
  std::int64_t frames = 0;
  double max_abs = 0;
  double sum_mean_abs = 0;
  double pixels = 0;
  double pixels_within_2 = 0;
  double mean_abs() const { return frames > 0 ? sum_mean_abs / static_cast<double>(frames) : 0; }
  double within_2() const { return pixels > 0 ? pixels_within_2 / pixels : 1; }
};

bool have_ffmpeg() {
  static const bool have = std::system("ffmpeg -hide_banner -version > /dev/null 2>&1") == 0;
  return have;
}

// ffmpeg -f lavfi -i testsrc2 -vf FILTER ... OUT: `args` are the encoding options.
bool ffmpeg_testsrc(const std::string& out, const std::string& filter, int frames, const std::string& args) {
  const std::string cmd = "ffmpeg -v error -y -f lavfi -i testsrc2=size=336x208:rate=25 -vf " + filter + " -frames:v " +
                          std::to_string(frames) + " " + args + " '" + out + "' < /dev/null";
  return std::system(cmd.c_str()) == 0 && fs::exists(out);
}

// Smooth random colour frames (codecs keep them close), each different.
std::vector<cv::Mat> colour_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, CV_8UC3);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(f, f, {7, 7}, 2.0);
    frames.push_back(f);
  }
  return frames;
}

bool write_video(const std::string& path, int fourcc, const std::vector<cv::Mat>& frames) {
  cv::VideoWriter w(path, cv::CAP_FFMPEG, fourcc, 25, frames.front().size(), true);
  if (!w.isOpened()) return false;
  for (const auto& f : frames) w.write(f);
  w.release();
  return fs::exists(path);
}

// Reads `path` with cv::VideoCapture (BGR) and with neopipe's reader in BGR and gray, in lockstep:
// the same frame count and sizes, BGR identical, gray within `tol` of cvtColor of the BGR.
Comparison compare_with_videocapture(const std::string& path, Tolerance tol) {
  Comparison c;
  cv::VideoCapture cap(path, cv::CAP_FFMPEG);
  EXPECT_TRUE(cap.isOpened()) << path;
  const auto bgr = io::open_frame_source({path}, io::ColorFormat::bgr);
  const auto gray = io::open_frame_source({path}, io::ColorFormat::gray);
  const double cap_count = cap.get(cv::CAP_PROP_FRAME_COUNT);
  EXPECT_EQ(bgr->frame_count().value_or(0), static_cast<std::int64_t>(cap_count > 0 ? cap_count : 0));
  EXPECT_EQ(gray->frame_count(), bgr->frame_count());
  EXPECT_EQ(bgr->fps(), cap.get(cv::CAP_PROP_FPS));
  EXPECT_EQ(bgr->description(), path);
  std::int64_t bgr_mismatches = 0;
  cv::Mat expected;
  while (cap.read(expected) && !expected.empty()) {
    const auto b = bgr->next();
    const auto g = gray->next();
    if (!b || !g) {
      ADD_FAILURE() << path << ": neopipe's reader ended at frame " << c.frames << ", cv::VideoCapture goes on";
      return c;
    }
    EXPECT_EQ(b->index, c.frames);
    EXPECT_EQ(g->index, c.frames);
    EXPECT_EQ(b->image.type(), CV_8UC3);
    EXPECT_EQ(g->image.type(), CV_8UC1);
    EXPECT_EQ(b->image.size(), expected.size());
    EXPECT_EQ(g->image.size(), expected.size());
    if (b->image.size() != expected.size() || g->image.size() != expected.size()) return c;
    if (!same_image(b->image, expected)) ++bgr_mismatches;
    cv::Mat expected_gray;
    cv::Mat diff;
    cv::cvtColor(expected, expected_gray, cv::COLOR_BGR2GRAY);
    cv::absdiff(g->image, expected_gray, diff);
    double max_abs = 0;
    cv::minMaxLoc(diff, nullptr, &max_abs);
    c.max_abs = std::max(c.max_abs, max_abs);
    c.sum_mean_abs += cv::mean(diff)[0];
    c.pixels += static_cast<double>(diff.total());
    c.pixels_within_2 += static_cast<double>(cv::countNonZero(diff <= 2));
    ++c.frames;
  }
  EXPECT_FALSE(bgr->next().has_value()) << path << ": neopipe's reader has more frames than cv::VideoCapture";
  EXPECT_FALSE(gray->next().has_value()) << path;
  EXPECT_EQ(bgr_mismatches, 0) << path << ": BGR frames that differ from cv::VideoCapture's";
  EXPECT_LE(c.max_abs, tol.max_abs) << path;
  EXPECT_LE(c.mean_abs(), tol.mean_abs) << path;
  EXPECT_GE(c.within_2(), tol.within_2) << path;
  std::printf("%s: %lld frames, gray vs cvtColor(VideoCapture BGR): max %.0f, mean %.4f, within 2: %.5f\n",
              fs::path(path).filename().c_str(), static_cast<long long>(c.frames), c.max_abs, c.mean_abs(),
              c.within_2());
  return c;
}

std::string source_error(const std::string& path, io::ColorFormat format) {
  try {
    const auto source = io::open_frame_source({path}, format);
    while (source->next()) {
    }
  } catch (const io::SourceError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << ": no SourceError";
  return {};
}

}  // namespace

TEST(LibavVideoSource, VtestAviMatchesVideoCapture) {
  if (!fs::exists(kVtest)) GTEST_SKIP() << kVtest << " is missing (Debian package opencv-doc; scripts/setup.sh)";
  const Comparison c = compare_with_videocapture(kVtest, {32, 1.5, 0.98});
  EXPECT_EQ(c.frames, 795);
}

TEST(LibavVideoSource, Mpeg4LimitedRangeMatchesVideoCapture) {
  const TempDir dir("neopipe_libav_mpeg4");
  const std::string path = dir.file("clip.mp4");
  ASSERT_TRUE(write_video(path, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), colour_frames(20, {320, 240}, 1)));
  const Comparison c = compare_with_videocapture(path, {6, 1.5, 0.99});
  EXPECT_EQ(c.frames, 20);
}

TEST(LibavVideoSource, MjpegFullRangeMatchesVideoCapture) {
  const TempDir dir("neopipe_libav_mjpeg");
  for (const cv::Size size : {cv::Size(320, 240), cv::Size(333, 201)}) {
    const std::string path = dir.file("clip_" + std::to_string(size.width) + ".avi");
    ASSERT_TRUE(write_video(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), colour_frames(12, size, 2)));
    const Comparison c = compare_with_videocapture(path, {3, 1.0, 0.999});
    EXPECT_EQ(c.frames, 12);
  }
}

// Through the ffmpeg tool: the planar and semi-planar formats, at an odd size, with sharp
// saturated colour edges (testsrc2); and a packed format (yuyv422), read through BGR for gray.
TEST(LibavVideoSource, PixelFormatsAtAnOddSizeMatchVideoCapture) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is missing (scripts/setup.sh installs it)";
  const TempDir dir("neopipe_libav_formats");
  const struct {
    const char* name;
    const char* args;
    Tolerance tol;
  } cases[] = {
      {"yuv420p.mkv", "-c:v ffv1 -pix_fmt yuv420p", {48, 0.75, 0.93}},
      {"yuv422p.mkv", "-c:v ffv1 -pix_fmt yuv422p", {48, 0.75, 0.93}},
      {"yuv444p.mkv", "-c:v ffv1 -pix_fmt yuv444p", {48, 0.75, 0.93}},
      {"nv12.nut", "-c:v rawvideo -pix_fmt nv12", {48, 0.75, 0.93}},
      {"yuvj420p.avi", "-c:v mjpeg -pix_fmt yuvj420p -q:v 3", {48, 0.75, 0.93}},
      {"gray.nut", "-c:v rawvideo -pix_fmt gray", {0, 0.0, 1.0}},
      {"yuyv422.nut", "-c:v rawvideo -pix_fmt yuyv422", {0, 0.0, 1.0}},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name);
    const std::string path = dir.file(k.name);
    ASSERT_TRUE(ffmpeg_testsrc(path, "scale=333:201", 8, k.args)) << "ffmpeg could not write " << k.name;
    const Comparison c = compare_with_videocapture(path, k.tol);
    EXPECT_EQ(c.frames, 8);
  }
}

// yuv420p flagged full range (as HEVC and VP9 decoders hand out full-range video): the reader takes
// the flag, for gray (Y as it is) and for BGR (swscale told the range), so gray stays close to
// cvtColor of its own BGR. cv::VideoCapture ignores the flag and stretches the contrast: its BGR
// differs from the reader's here, and only here.
TEST(LibavVideoSource, FullRangeFlagOnAPlainYuvFormatIsHonoured) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is missing (scripts/setup.sh installs it)";
  const TempDir dir("neopipe_libav_full_range_flag");
  const std::string path = dir.file("full.mkv");
  // Colours at 40 % saturation: most of testsrc2's bars are so saturated that they clip to the same
  // BGR under either range, which would hide the difference.
  ASSERT_TRUE(
      ffmpeg_testsrc(path, "hue=s=0.4,scale=333:201:out_range=pc", 4, "-c:v ffv1 -pix_fmt yuv420p -color_range pc"));
  const auto bgr = io::open_frame_source({path}, io::ColorFormat::bgr);
  const auto gray = io::open_frame_source({path}, io::ColorFormat::gray);
  cv::VideoCapture cap(path, cv::CAP_FFMPEG);
  int frames = 0;
  while (auto b = bgr->next()) {
    const auto g = gray->next();
    ASSERT_TRUE(g.has_value());
    cv::Mat expected_gray;
    cv::Mat diff;
    cv::cvtColor(b->image, expected_gray, cv::COLOR_BGR2GRAY);
    cv::absdiff(g->image, expected_gray, diff);
    // Measured: mean 0.003, 99.96 % within 2 levels; gray against cv::VideoCapture's: mean 9.0.
    EXPECT_LT(cv::mean(diff)[0], 0.1) << "frame " << frames;
    EXPECT_GE(cv::countNonZero(diff <= 2), static_cast<int>(diff.total() * 99 / 100)) << "frame " << frames;
    cv::Mat opencv;
    ASSERT_TRUE(cap.read(opencv));
    cv::Mat opencv_gray;
    cv::cvtColor(opencv, opencv_gray, cv::COLOR_BGR2GRAY);
    cv::absdiff(g->image, opencv_gray, diff);
    EXPECT_GT(cv::mean(diff)[0], 3.0) << "cv::VideoCapture took the range flag after all? frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, 4);
}

// A display matrix turns the frames as FFmpeg's tools turn them: the same bitstream with "rotate=90"
// (a matrix of 90 degrees counter-clockwise) reads as the plain file's frames turned that way.
// (OpenCV 4.6 turns them clockwise, the other way round, so cv::VideoCapture is no reference here.)
TEST(LibavVideoSource, DisplayMatrixTurnsTheFrames) {
  if (!have_ffmpeg()) GTEST_SKIP() << "the ffmpeg tool is missing (scripts/setup.sh installs it)";
  const TempDir dir("neopipe_libav_rotation");
  const std::string plain = dir.file("plain.mp4");
  const std::string turned = dir.file("turned.mp4");
  ASSERT_TRUE(ffmpeg_testsrc(plain, "scale=320:240", 5, "-c:v mpeg4"));
  const std::string cmd =
      "ffmpeg -v error -y -i '" + plain + "' -c copy -metadata:s:v:0 rotate=90 '" + turned + "' < /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  for (const auto format : {io::ColorFormat::gray, io::ColorFormat::bgr}) {
    const auto a = io::open_frame_source({plain}, format);
    const auto b = io::open_frame_source({turned}, format);
    int frames = 0;
    while (auto fa = a->next()) {
      const auto fb = b->next();
      ASSERT_TRUE(fb.has_value());
      cv::Mat expected;
      cv::rotate(fa->image, expected, cv::ROTATE_90_COUNTERCLOCKWISE);
      EXPECT_EQ(fb->image.size(), cv::Size(240, 320));
      EXPECT_TRUE(same_image(fb->image, expected)) << "frame " << frames;
      ++frames;
    }
    EXPECT_FALSE(b->next().has_value());
    EXPECT_EQ(frames, 5);
  }
}

TEST(LibavVideoSource, EveryFrameIsFreshlyAllocated) {
  const TempDir dir("neopipe_libav_fresh");
  const std::string path = dir.file("clip.avi");
  ASSERT_TRUE(write_video(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), colour_frames(6, {64, 48}, 3)));
  for (const auto format : {io::ColorFormat::gray, io::ColorFormat::bgr}) {
    const auto source = io::open_frame_source({path}, format);
    std::vector<cv::Mat> kept;
    std::vector<cv::Mat> copies;
    while (auto f = source->next()) {
      EXPECT_TRUE(f->image.isContinuous());
      EXPECT_EQ(f->image.u->refcount, 1) << "frame " << f->index << " shares its pixels";
      copies.push_back(f->image.clone());
      kept.push_back(std::move(f->image));
    }
    ASSERT_EQ(kept.size(), 6U);
    for (size_t i = 0; i < kept.size(); ++i) {
      EXPECT_TRUE(same_image(kept[i], copies[i])) << "frame " << i << " changed after later frames were read";
      if (i > 0) {
        EXPECT_NE(kept[i].data, kept[i - 1].data);
      }
    }
  }
}

// One decoder thread on one or two cores (each FFmpeg frame thread holds a decoded picture and
// gains the run nothing there), else one per core up to FFmpeg's 16, as cv::VideoCapture.
TEST(LibavVideoSource, DecoderThreadsAreOnePerCoreExceptOnSmallMachines) {
  EXPECT_EQ(io::decoder_threads(1), 1);
  EXPECT_EQ(io::decoder_threads(2), 1);
  EXPECT_EQ(io::decoder_threads(3), 3);
  EXPECT_EQ(io::decoder_threads(8), 8);
  EXPECT_EQ(io::decoder_threads(16), 16);
  EXPECT_EQ(io::decoder_threads(64), 16);
}

TEST(LibavVideoSource, TruncatedVideoIsASourceErrorNamingTheFile) {
  const TempDir dir("neopipe_libav_truncated");
  // MJPG in AVI: the index is lost, the frames before the cut decode, then the count falls short.
  const std::string avi = dir.file("cut.avi");
  ASSERT_TRUE(write_video(avi, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), colour_frames(30, {64, 48}, 4)));
  fs::resize_file(avi, fs::file_size(avi) / 2);
  for (const auto format : {io::ColorFormat::gray, io::ColorFormat::bgr}) {
    const std::string message = source_error(avi, format);
    EXPECT_EQ(message.rfind(avi + ": decoding stopped at frame ", 0), 0U) << message;
    EXPECT_NE(message.find(" of 30 (truncated or corrupt video"), std::string::npos) << message;
  }
  // MPEG-4 in MP4 written by OpenCV: the index (moov) is at the end, so the cut file does not open.
  const std::string mp4 = dir.file("cut.mp4");
  ASSERT_TRUE(write_video(mp4, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), colour_frames(30, {64, 48}, 5)));
  fs::resize_file(mp4, fs::file_size(mp4) * 8 / 10);
  const std::string message = source_error(mp4, io::ColorFormat::gray);
  EXPECT_EQ(message.rfind(mp4 + ": ", 0), 0U) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(LibavVideoSource, TextFileNamedMp4IsASourceError) {
  const TempDir dir("neopipe_libav_text");
  const std::string path = dir.file("notes.mp4");
  std::ofstream(path) << "these are words, not a video\n";
  const std::string message = source_error(path, io::ColorFormat::gray);
  EXPECT_EQ(message.rfind(path + ": neither an image nor a video neopipe can read (FFmpeg: ", 0), 0U) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}
