// Tests of the media plug-in (pipeline/media/media.hpp) and of telling images from videos without it
// (pipeline/io/image_signature.hpp):
//   * has_image_signature agrees with cv::haveImageReader on a file of every format this OpenCV
//     writes (also under a name without extension), and on files that are not images: videos, text,
//     an empty file, random bytes, near misses of the signatures;
//   * read_image / write_image give what cv::imread / cv::imwrite give, and report failures as
//     results (empty Mat, false) where OpenCV would throw;
//   * a video written through the plug-in reads back through neopipe's own reader, frame for frame;
//   * fourcc_for picks Motion JPEG for .avi and MPEG-4 otherwise.

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
#include "pipeline/io/image_signature.hpp"
#include "pipeline/io/libav_video_source.hpp"
#include "pipeline/media/media.hpp"

namespace io = neopipe::pipeline::io;
namespace media = neopipe::pipeline::media;
namespace fs = std::filesystem;

namespace {

class Media : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "neopipe_media_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write_bytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }

  fs::path dir_;
};

cv::Mat test_image(int type = CV_8UC3) {
  cv::Mat img(48, 64, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(img, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(img, img, {5, 5}, 1.5);
  if (type == CV_32FC3) img.convertTo(img, CV_32FC3, 1.0 / 255);
  if (type == CV_8UC1) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  return img;
}

bool opencv_writes(const std::string& path, const cv::Mat& img) {
  try {
    return cv::imwrite(path, img);
  } catch (const cv::Exception&) {
    return false;  // a codec this build of OpenCV lacks (or refuses by default, as OpenEXR)
  }
}

}  // namespace

TEST_F(Media, SignatureAgreesWithOpenCvOnEveryFormatItWrites) {
  struct Format {
    const char* ext;
    int type;
  };
  const std::vector<Format> formats{{".png", CV_8UC3}, {".jpg", CV_8UC3},  {".jp2", CV_8UC3},  {".bmp", CV_8UC3},
                                    {".tif", CV_8UC3}, {".webp", CV_8UC3}, {".pgm", CV_8UC1},  {".ppm", CV_8UC3},
                                    {".pbm", CV_8UC1}, {".pam", CV_8UC3},  {".pfm", CV_32FC3}, {".hdr", CV_32FC3},
                                    {".sr", CV_8UC3},  {".ras", CV_8UC3},  {".exr", CV_32FC3}};
  int written = 0;
  for (const auto& f : formats) {
    const std::string file = path(std::string("image") + f.ext);
    if (!opencv_writes(file, test_image(f.type))) continue;
    ++written;
    const std::string bare = path(std::string("image_no_extension_") + (f.ext + 1));
    fs::copy_file(file, bare);
    for (const auto& p : {file, bare}) {
      EXPECT_TRUE(cv::haveImageReader(p)) << p;
      EXPECT_TRUE(io::file_has_image_signature(p)) << p;
      EXPECT_TRUE(io::is_image_file(p)) << p;
    }
  }
  EXPECT_GE(written, 10) << "this OpenCV writes fewer formats than Debian's 4.6 does";
}

TEST_F(Media, SignatureAgreesWithOpenCvOnFilesThatAreNotImages) {
  write_bytes("text.png", "not an image\n");
  write_bytes("empty", "");
  write_bytes("P7", "P7");                                             // too short to be Netpbm
  write_bytes("P8", "P8\n1 1\n");                                      // no such Netpbm kind
  write_bytes("RIFF.avi", std::string("RIFF\x10\0\0\0AVI LIST", 16));  // a RIFF that is not WebP
  write_bytes("II", "II*");                                            // TIFF wants a fourth byte, 0
  std::string noise(4096, '\0');
  cv::RNG rng(3);
  for (auto& c : noise) c = static_cast<char>(rng.uniform(0, 256));
  noise[0] = 'x';  // random bytes could start as a signature only by this test's bad luck
  write_bytes("noise.bin", noise);
  cv::VideoWriter w(path("video.avi"), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, {64, 48});
  ASSERT_TRUE(w.isOpened());
  w.write(test_image());
  w.release();
  std::vector<std::string> files{"text.png", "empty", "P7", "P8", "RIFF.avi", "II", "noise.bin", "video.avi"};
  const std::string vtest = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";
  for (const auto& name : files) {
    const std::string p = path(name);
    EXPECT_FALSE(cv::haveImageReader(p)) << p;
    EXPECT_FALSE(io::file_has_image_signature(p)) << p;
  }
  if (fs::exists(vtest)) {
    EXPECT_FALSE(io::file_has_image_signature(vtest));
  }
  EXPECT_FALSE(io::file_has_image_signature(path("no such file")));
}

TEST(ImageSignature, NearMissesOfTheSignatures) {
  EXPECT_TRUE(io::has_image_signature("P5\n2 2\n255\n"));
  EXPECT_TRUE(io::has_image_signature("Pf 2 2\n"));
  EXPECT_FALSE(io::has_image_signature("P5x"));  // Netpbm wants white space after the kind
  EXPECT_FALSE(io::has_image_signature("P0\n"));
  EXPECT_TRUE(io::has_image_signature(std::string("RIFF\0\0\0\0WEBPVP8 ", 16)));
  EXPECT_FALSE(io::has_image_signature(std::string("RIFF\0\0\0\0WEB", 11)));
  EXPECT_TRUE(io::has_image_signature(std::string(128, '\0') + "DICM"));
  EXPECT_FALSE(io::has_image_signature(std::string(128, '\0') + "DIC"));
  EXPECT_FALSE(io::has_image_signature("\x89PNG\r\n"));  // cut short
  EXPECT_FALSE(io::has_image_signature(""));
}

TEST_F(Media, ReadsAndWritesImagesAsOpenCvDoes) {
  const cv::Mat img = test_image();
  ASSERT_TRUE(media::write_image(path("a.png"), img));
  const cv::Mat back = cv::imread(path("a.png"), cv::IMREAD_COLOR);
  ASSERT_EQ(back.size(), img.size());
  EXPECT_EQ(cv::norm(back, img, cv::NORM_INF), 0);
  ASSERT_TRUE(cv::imwrite(path("b.jpg"), img));
  for (const auto mode : {media::ImageMode::color, media::ImageMode::gray}) {
    const cv::Mat ours = media::read_image(path("b.jpg"), mode);
    const cv::Mat theirs =
        cv::imread(path("b.jpg"), mode == media::ImageMode::color ? cv::IMREAD_COLOR : cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(ours.type(), theirs.type());
    EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0);
  }
  EXPECT_TRUE(media::have_image_reader(path("b.jpg")));
  EXPECT_TRUE(media::plugin_loaded());
}

TEST_F(Media, FailuresAreResultsNotExceptions) {
  const cv::Mat img = test_image();
  EXPECT_FALSE(media::write_image(path("no/such/dir/a.png"), img));
  EXPECT_FALSE(media::write_image(path("a.unknown"), img));  // cv::imwrite throws here
  write_bytes("text.png", "not an image\n");
  EXPECT_TRUE(media::read_image(path("text.png"), media::ImageMode::color).empty());
  EXPECT_TRUE(media::read_image(path("missing.png"), media::ImageMode::gray).empty());
  EXPECT_FALSE(media::have_image_reader(path("text.png")));
  EXPECT_EQ(media::open_video_writer(path("no/such/dir/a.mp4"), 25, {64, 48}), nullptr);
  EXPECT_EQ(media::open_video_reader(path("missing.mp4")), nullptr);
}

TEST_F(Media, VideoWrittenThroughThePluginReadsBackFrameForFrame) {
  for (const std::string name : {"v.avi", "v.mp4"}) {
    std::vector<cv::Mat> frames;
    {
      const auto writer = media::open_video_writer(path(name), 25, {64, 48});
      ASSERT_NE(writer, nullptr) << name;
      for (int k = 0; k < 5; ++k) {
        cv::Mat f(48, 64, CV_8UC3, cv::Scalar::all(40 * k + 20));
        writer->write(f);
        frames.push_back(f);
      }
    }  // the writer's destructor finishes the file
    io::LibavVideoSource source(path(name), io::ColorFormat::bgr);
    std::size_t n = 0;
    while (auto f = source.next()) {
      ASSERT_LT(n, frames.size()) << name;
      EXPECT_LT(cv::norm(f->image, frames[n], cv::NORM_INF), 8) << name << " frame " << n;
      ++n;
    }
    EXPECT_EQ(n, frames.size()) << name;
    const auto reader = media::open_video_reader(path(name));
    ASSERT_NE(reader, nullptr);
    cv::Mat f;
    std::size_t m = 0;
    while (reader->read(f)) ++m;
    EXPECT_EQ(m, frames.size()) << name;
  }
}

TEST(MediaFourcc, MotionJpegForAviMpeg4Otherwise) {
  EXPECT_EQ(media::fourcc_for("x/y.avi"), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'));
  EXPECT_EQ(media::fourcc_for("x/y.AVI"), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'));
  EXPECT_EQ(media::fourcc_for("y.mp4"), cv::VideoWriter::fourcc('m', 'p', '4', 'v'));
  EXPECT_EQ(media::fourcc_for("y.mkv"), cv::VideoWriter::fourcc('m', 'p', '4', 'v'));
}
