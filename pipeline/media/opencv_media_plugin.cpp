// The media plug-in: MediaBackend over OpenCV's imgcodecs and videoio. It is a module of its own,
// dlopen'ed by media.cpp on first use, because those two OpenCV modules pull in about 240 shared
// libraries (GDAL, GDCM, GStreamer, poppler, ...): linked into the program they cost every run
// 0.15 s of start-up and about 33 MB of resident memory, also runs that never touch an image file.

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "pipeline/media/media_backend.hpp"

namespace {
using neopipe::pipeline::media::ImageMode;
using neopipe::pipeline::media::MediaBackend;

class OpenCvVideoWriter final : public neopipe::pipeline::media::VideoWriter {
 public:
  bool open(const std::string& path, int fourcc, double fps, cv::Size size) {
    return writer_.open(path, cv::CAP_FFMPEG, fourcc, fps, size, true);
  }
  void write(const cv::Mat& frame) override { writer_.write(frame); }

 private:
  cv::VideoWriter writer_;
};

class OpenCvVideoReader final : public neopipe::pipeline::media::VideoReader {
 public:
  bool open(const std::string& path) { return capture_.open(path, cv::CAP_FFMPEG); }
  bool read(cv::Mat& frame) override { return capture_.read(frame) && !frame.empty(); }

 private:
  cv::VideoCapture capture_;
};

class OpenCvMedia final : public MediaBackend {
 public:
  cv::Mat read_image(const std::string& path, ImageMode mode) const override {
    try {
      return cv::imread(path, mode == ImageMode::color ? cv::IMREAD_COLOR : cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception&) {
      return {};
    }
  }

  bool write_image(const std::string& path, const cv::Mat& image) const override {
    try {
      return cv::imwrite(path, image);
    } catch (const cv::Exception&) {
      return false;
    }
  }

  bool have_image_reader(const std::string& path) const override {
    try {
      return cv::haveImageReader(path);
    } catch (const cv::Exception&) {
      return false;
    }
  }

  std::unique_ptr<neopipe::pipeline::media::VideoWriter> open_video_writer(const std::string& path, int fourcc,
                                                                           double fps, cv::Size size) const override {
    try {
      auto writer = std::make_unique<OpenCvVideoWriter>();
      if (!writer->open(path, fourcc, fps, size)) return nullptr;
      return writer;
    } catch (const cv::Exception&) {
      return nullptr;
    }
  }

  std::unique_ptr<neopipe::pipeline::media::VideoReader> open_video_reader(const std::string& path) const override {
    try {
      auto reader = std::make_unique<OpenCvVideoReader>();
      if (!reader->open(path)) return nullptr;
      return reader;
    } catch (const cv::Exception&) {
      return nullptr;
    }
  }
};

}  // namespace

extern "C" __attribute__((visibility("default"))) const MediaBackend* neopipe_media_backend(int* version) {
  *version = neopipe::pipeline::media::kMediaBackendVersion;
  static const OpenCvMedia backend;
  return &backend;
}
