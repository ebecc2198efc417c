// Tests of frame sources (pipeline/io/frame_source.hpp, io::open_frame_source). Files are made by
// the test in a temporary folder: PNG/BMP images, a lossless FFV1 .mkv and an MJPG .avi written
// with cv::VideoWriter (FFmpeg). Checked: a directory is read in name order and only its image
// files are taken; explicit image files keep the order given; frames carry indices 0, 1, ...;
// frame_count(), fps() and description(); bgr and gray formats (a gray frame must equal
// cv::cvtColor(BGR2GRAY) of the bgr frame; from a YUV video, within a few levels). Every failure is
// a SourceError naming the path: a missing path, text files named .png or .mp4, an empty directory
// or one without images, a video given with an image, an image sequence whose second image has
// another size, a corrupt image in a directory, a video with no frames, and a truncated video, which
// must fail loudly rather than end early as if it were complete.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "pipeline/io/frame_source.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)
namespace io = neopipe::pipeline::io;
namespace fs = std::filesystem;

namespace {

// Smooth random colour images (so that JPEG-style codecs keep them close), all different.
std::vector<cv::Mat> colour_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, CV_8UC3);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(f, f, {5, 5}, 1.5);
    frames.push_back(f);
  }
  return frames;
}

void write_image(const std::string& path, const cv::Mat& image) {
  ASSERT_TRUE(cv::imwrite(path, image)) << path;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Writes `frames` as a video through OpenCV's FFmpeg backend; false if it could not.
bool write_video(const std::string& path, int fourcc, const std::vector<cv::Mat>& frames, cv::Size size,
                 double fps = 25) {
  cv::VideoWriter w(path, cv::CAP_FFMPEG, fourcc, fps, size, true);
  if (!w.isOpened()) return false;
  for (const auto& f : frames) w.write(f);
  w.release();
  return fs::exists(path);
}

const int kFfv1 = cv::VideoWriter::fourcc('F', 'F', 'V', '1');
const int kMjpg = cv::VideoWriter::fourcc('M', 'J', 'P', 'G');

std::vector<io::SourceFrame> read_all(io::FrameSource& source) {
  std::vector<io::SourceFrame> frames;
  while (auto f = source.next()) frames.push_back(std::move(*f));
  return frames;
}

// Opens `inputs` and reads every frame, expecting a SourceError on the way; returns its message.
std::string source_error(const std::vector<std::string>& inputs, io::ColorFormat format = io::ColorFormat::bgr) {
  try {
    auto source = io::open_frame_source(inputs, format);
    (void)read_all(*source);
  } catch (const io::SourceError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SourceError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no error";
  return {};
}

cv::Mat gray_of(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Image sequences

TEST(ImageSequence, DirectoryInNameOrderImagesOnly) {
  const TempDir dir("neopipe_sources_dir");
  const auto frames = colour_frames(4, {16, 12}, 1);
  // Written out of order, with mixed extensions and case; sorted by name they are F00, f01, f02, f03.
  write_image(dir.file("f03.png"), frames[3]);
  write_image(dir.file("F00.PNG"), frames[0]);
  write_image(dir.file("f02.bmp"), frames[2]);
  write_image(dir.file("f01.png"), frames[1]);
  write_text(dir.file("notes.txt"), "not an image");
  write_text(dir.file("f015.yaml"), "nodes: []");
  fs::create_directories(dir.file("sub.png"));  // a directory with an image name
  write_image(dir.file("sub.png/inner.png"), frames[0]);

  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  EXPECT_EQ(source->frame_count(), std::optional<std::int64_t>(4));
  EXPECT_EQ(source->fps(), 0);
  EXPECT_EQ(source->description(), "4 images from " + dir.str());
  const auto got = read_all(*source);
  ASSERT_EQ(got.size(), 4U);
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].index, static_cast<std::int64_t>(i));
    EXPECT_TRUE(same_image(got[i].image, frames[i])) << "frame " << i;
  }
  EXPECT_FALSE(source->next().has_value());  // stays at the end
  EXPECT_FALSE(source->next().has_value());
}

TEST(ImageSequence, ExplicitFilesInTheGivenOrder) {
  const TempDir dir("neopipe_sources_files");
  const auto frames = colour_frames(3, {10, 8}, 2);
  const std::vector<std::string> files{dir.file("c.png"), dir.file("a.png"), dir.file("b.bmp")};
  for (size_t i = 0; i < files.size(); ++i) write_image(files[i], frames[i]);

  auto source = io::open_frame_source(files, io::ColorFormat::bgr);
  EXPECT_EQ(source->frame_count(), std::optional<std::int64_t>(3));
  EXPECT_EQ(source->description(), "3 images from " + files[0] + ", ...");
  const auto got = read_all(*source);
  ASSERT_EQ(got.size(), 3U);
  for (size_t i = 0; i < 3; ++i) EXPECT_TRUE(same_image(got[i].image, frames[i])) << "frame " << i;
  // Every frame is freshly allocated.
  EXPECT_NE(got[0].image.data, got[1].image.data);

  // One file: described by its path. A directory and a file: the directory's images, then the file.
  EXPECT_EQ(io::open_frame_source({files[1]}, io::ColorFormat::bgr)->description(), files[1]);
  const TempDir sub("neopipe_sources_files_sub");
  write_image(sub.file("x.png"), frames[2]);
  write_image(sub.file("y.png"), frames[1]);
  auto mixed = io::open_frame_source({sub.str(), files[0]}, io::ColorFormat::bgr);
  const auto m = read_all(*mixed);
  ASSERT_EQ(m.size(), 3U);
  EXPECT_TRUE(same_image(m[0].image, frames[2]));
  EXPECT_TRUE(same_image(m[1].image, frames[1]));
  EXPECT_TRUE(same_image(m[2].image, frames[0]));
}

TEST(ImageSequence, GrayImagesInBothFormats) {
  const TempDir dir("neopipe_sources_gray_png");
  cv::Mat gray(12, 16, CV_8UC1);
  cv::randu(gray, 0, 256);
  write_image(dir.file("g.png"), gray);
  auto as_gray = io::open_frame_source({dir.file("g.png")}, io::ColorFormat::gray);
  const auto g = read_all(*as_gray);
  ASSERT_EQ(g.size(), 1U);
  EXPECT_TRUE(same_image(g[0].image, gray));
  auto as_bgr = io::open_frame_source({dir.file("g.png")}, io::ColorFormat::bgr);
  const auto b = read_all(*as_bgr);
  ASSERT_EQ(b.size(), 1U);
  ASSERT_EQ(b[0].image.type(), CV_8UC3);
  std::vector<cv::Mat> channels;
  cv::split(b[0].image, channels);
  for (const auto& c : channels) EXPECT_TRUE(same_image(c, gray));
}

// A gray frame from an image file is cv::cvtColor(BGR2GRAY) of its bgr frame, as from a video.
// (Regression: cv::imread(IMREAD_GRAYSCALE) uses each codec's own luma arithmetic; for random colour
// PNGs about half the pixels were off by 1, for JPEG up to 5.)
TEST(ImageSequence, GrayFrameEqualsCvtColorOfTheBgrFrame) {
  const TempDir dir("neopipe_sources_gray_vs_bgr");
  const auto frames = colour_frames(3, {40, 30}, 5);
  write_image(dir.file("a.png"), frames[0]);
  write_image(dir.file("b.bmp"), frames[1]);
  write_image(dir.file("c.jpg"), frames[2]);
  auto bgr = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  auto gray = io::open_frame_source({dir.str()}, io::ColorFormat::gray);
  const auto b = read_all(*bgr);
  const auto g = read_all(*gray);
  ASSERT_EQ(b.size(), 3U);
  ASSERT_EQ(g.size(), 3U);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(same_image(g[i].image, gray_of(b[i].image)))
        << "frame " << i << ": " << cv::countNonZero(g[i].image != gray_of(b[i].image)) << " pixels differ";
  }
}

// ---------------------------------------------------------------------------------------------
// Videos

TEST(VideoSource, LosslessVideoFramesCountAndRate) {
  const TempDir dir("neopipe_sources_ffv1");
  const std::string path = dir.file("clip.mkv");
  const auto frames = colour_frames(10, {32, 24}, 6);
  ASSERT_TRUE(write_video(path, kFfv1, frames, {32, 24}, 25)) << "cannot write FFV1 with OpenCV's FFmpeg backend";
  auto source = io::open_frame_source({path}, io::ColorFormat::bgr);
  EXPECT_EQ(source->description(), path);
  EXPECT_EQ(source->fps(), 25);
  EXPECT_EQ(source->frame_count(), std::optional<std::int64_t>(10));
  const auto got = read_all(*source);
  ASSERT_EQ(got.size(), 10U);
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].index, static_cast<std::int64_t>(i));
    EXPECT_TRUE(same_image(got[i].image, frames[i])) << "frame " << i;  // FFV1 is lossless
  }
  EXPECT_FALSE(source->next().has_value());
  EXPECT_FALSE(source->next().has_value());
}

// OpenCV's FFV1 holds RGB pixels, which the reader takes to gray through BGR: exactly cvtColor of
// the BGR frame. MJPG holds YUV, whose gray is the luma plane: within a few gray levels of it (see
// test_libav_video_source.cpp for why and for more formats).
TEST(VideoSource, GrayFrameEqualsCvtColorOfTheBgrFrame) {
  const TempDir dir("neopipe_sources_video_gray");
  const std::string mkv = dir.file("clip.mkv");
  const std::string avi = dir.file("clip.avi");
  const auto frames = colour_frames(12, {48, 32}, 7);
  ASSERT_TRUE(write_video(mkv, kFfv1, frames, {48, 32}, 30));
  ASSERT_TRUE(write_video(avi, kMjpg, frames, {48, 32}, 12.5));
  for (const auto& path : {mkv, avi}) {
    SCOPED_TRACE(path);
    auto bgr = io::open_frame_source({path}, io::ColorFormat::bgr);
    auto gray = io::open_frame_source({path}, io::ColorFormat::gray);
    const auto b = read_all(*bgr);
    const auto g = read_all(*gray);
    ASSERT_EQ(b.size(), frames.size());
    ASSERT_EQ(g.size(), frames.size());
    for (size_t i = 0; i < frames.size(); ++i) {
      ASSERT_EQ(b[i].image.type(), CV_8UC3);
      ASSERT_EQ(g[i].image.type(), CV_8UC1);
      if (path == mkv) {
        EXPECT_TRUE(same_image(g[i].image, gray_of(b[i].image))) << "frame " << i;
      } else {
        EXPECT_LE(cv::norm(g[i].image, gray_of(b[i].image), cv::NORM_INF), 3) << "frame " << i;
      }
    }
  }
  EXPECT_EQ(io::open_frame_source({avi}, io::ColorFormat::bgr)->fps(), 12.5);
}

// ---------------------------------------------------------------------------------------------
// Errors: a SourceError naming the path

TEST(FrameSourceErrors, MissingPathOrNoInput) {
  const TempDir dir("neopipe_sources_missing");
  const std::string missing = dir.file("nope.mp4");
  EXPECT_EQ(source_error({missing}), missing + ": no such file or directory");
  EXPECT_EQ(source_error({}), "no input given");
  write_image(dir.file("ok.png"), colour_frames(1, {4, 4}, 9)[0]);
  EXPECT_EQ(source_error({dir.file("ok.png"), missing}), missing + ": no such file or directory");
}

TEST(FrameSourceErrors, TextFilesWithMediaNames) {
  const TempDir dir("neopipe_sources_text");
  for (const char* name : {"fake.png", "fake.jpg"}) {
    SCOPED_TRACE(name);
    const std::string path = dir.file(name);
    write_text(path, "these are words, not pixels\n");
    EXPECT_EQ(source_error({path}), path + ": not an image OpenCV can read (unknown format or corrupt file)");
  }
  for (const char* name : {"fake.mp4", "fake.avi"}) {
    SCOPED_TRACE(name);
    const std::string path = dir.file(name);
    write_text(path, "these are words, not pixels\n");
    const std::string message = source_error({path});
    EXPECT_EQ(message.rfind(path + ": neither an image nor a video neopipe can read (FFmpeg: ", 0), 0U) << message;
  }
  // A text file with an image name inside a directory is taken by its name and fails when read.
  const TempDir seq("neopipe_sources_text_in_dir");
  write_image(seq.file("a.png"), colour_frames(1, {6, 6}, 10)[0]);
  write_text(seq.file("b.png"), "not a png");
  auto source = io::open_frame_source({seq.str()}, io::ColorFormat::bgr);
  ASSERT_TRUE(source->next().has_value());
  try {
    (void)source->next();
    ADD_FAILURE() << "b.png was read";
  } catch (const io::SourceError& e) {
    EXPECT_EQ(std::string(e.what()),
              seq.file("b.png") + ": not an image OpenCV can read (unknown format or corrupt file)");
  }
}

TEST(FrameSourceErrors, DirectoriesWithoutImages) {
  const TempDir empty("neopipe_sources_empty_dir");
  EXPECT_EQ(source_error({empty.str()}), empty.str() + ": the directory holds no image files");
  const TempDir other("neopipe_sources_no_images");
  write_text(other.file("readme.txt"), "hello");
  write_text(other.file("data.csv"), "1,2,3");
  fs::create_directories(other.file("frames.png"));
  write_image(other.file("frames.png/a.png"), colour_frames(1, {4, 4}, 11)[0]);  // not searched
  EXPECT_EQ(source_error({other.str()}), other.str() + ": the directory holds no image files");
}

TEST(FrameSourceErrors, VideoTogetherWithImages) {
  const TempDir dir("neopipe_sources_mixed");
  const std::string video = dir.file("clip.mkv");
  const std::string image = dir.file("still.png");
  const auto frames = colour_frames(2, {16, 16}, 12);
  ASSERT_TRUE(write_video(video, kFfv1, frames, {16, 16}));
  write_image(image, frames[0]);
  const std::string expected = video + ": give one video, or any number of images (2 inputs were given)";
  EXPECT_EQ(source_error({video, image}), expected);
  EXPECT_EQ(source_error({image, video}), expected);
  EXPECT_EQ(source_error({video, video}), expected);
}

TEST(FrameSourceErrors, SecondImageOfAnotherSize) {
  const TempDir dir("neopipe_sources_sizes");
  const std::string first = dir.file("a.png");
  const std::string second = dir.file("b.png");
  write_image(first, colour_frames(1, {16, 12}, 13)[0]);
  write_image(second, colour_frames(1, {20, 10}, 14)[0]);
  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::gray);
  ASSERT_TRUE(source->next().has_value());
  try {
    (void)source->next();
    ADD_FAILURE() << "an image of another size was accepted";
  } catch (const io::SourceError& e) {
    EXPECT_EQ(std::string(e.what()), second + ": the image is 20x10 but the sequence started at 16x12 (" + first + ")");
  }
}

TEST(FrameSourceErrors, VideoWithoutFrames) {
  const TempDir dir("neopipe_sources_empty_video");
  const std::string path = dir.file("empty.avi");
  ASSERT_TRUE(write_video(path, kMjpg, {}, {32, 24}));
  ASSERT_GT(fs::file_size(path), 0U);  // a container header, no frames
  EXPECT_EQ(source_error({path}), path + ": the video has no frames");
  // Cut to a fraction of its header: not a readable video at all.
  const std::string cut = dir.file("cut.avi");
  fs::copy_file(path, cut);
  fs::resize_file(cut, 100);
  const std::string message = source_error({cut});
  EXPECT_EQ(message.rfind(cut + ": ", 0), 0U) << message;
}

TEST(FrameSourceErrors, TruncatedVideoIsAnErrorNotAnEarlyEnd) {
  const TempDir dir("neopipe_sources_truncated");
  const std::string path = dir.file("clip.avi");
  const auto frames = colour_frames(30, {64, 48}, 15);
  ASSERT_TRUE(write_video(path, kMjpg, frames, {64, 48}));
  const auto full = fs::file_size(path);
  fs::resize_file(path, full * 6 / 10);

  auto source = io::open_frame_source({path}, io::ColorFormat::bgr);
  EXPECT_EQ(source->frame_count(), std::optional<std::int64_t>(30));  // what the header promises
  std::int64_t read = 0;
  try {
    while (source->next()) ++read;
    ADD_FAILURE() << "the truncated video ended quietly after " << read << " frames";
  } catch (const io::SourceError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0U) << message;
    EXPECT_NE(message.find("truncated or corrupt"), std::string::npos) << message;
    EXPECT_NE(message.find("of 30"), std::string::npos) << message;
  }
  EXPECT_GT(read, 0);
  EXPECT_LT(read, 30);
  // The frames before the damage are still delivered, in gray too, and the end is still an error.
  auto gray = io::open_frame_source({path}, io::ColorFormat::gray);
  std::int64_t gray_read = 0;
  EXPECT_THROW(
      {
        while (gray->next()) ++gray_read;
      },
      io::SourceError);
  EXPECT_EQ(gray_read, read);
}

TEST(FrameSource, ImageExtensions) {
  for (const char* yes :
       {"a.png", "b.PNG", "c.jpg", "d.JPEG", "e.bmp", "f.tif", "g.tiff", "h.pgm", "i.webp", "j.ppm"}) {
    EXPECT_TRUE(io::has_image_extension(yes)) << yes;
  }
  for (const char* no : {"a.mp4", "b.avi", "c.mkv", "noext", "png", "dir.png/file", "a.png.txt", "a.yaml"}) {
    EXPECT_FALSE(io::has_image_extension(no)) << no;
  }
}
