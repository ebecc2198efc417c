#pragma once
// Image and video files through OpenCV's codecs (imgcodecs, videoio), loaded on first use.
//
// Those two OpenCV modules bring about 240 shared libraries with them (GDAL, GDCM, GStreamer,
// poppler, ...). Linked into the program they cost every run 0.15 s of start-up and about 33 MB of
// resident memory, also `neopipe run VIDEO`, which decodes with FFmpeg's libraries directly and
// never needs them. So they live in a plug-in, libneopipe_media.so (opencv_media_plugin.cpp), that
// the first call below loads: from $NEOPIPE_MEDIA_PLUGIN if set, else from the running program's
// directory, else from ../lib/neopipe/ beside it (an installed tree), else from where the build put
// it. It stays loaded until the process ends.
//
// Every function throws MediaError (naming `path`) if the plug-in cannot be loaded; otherwise
// failures are results, as documented, and never OpenCV exceptions.

#include <memory>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace neopipe::pipeline::media {

class MediaError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How an image is decoded: 8-bit BGR (cv::IMREAD_COLOR) or the codec's own gray (IMREAD_GRAYSCALE).
enum class ImageMode { color, gray };

class VideoWriter {
 public:
  virtual ~VideoWriter() = default;
  /// One BGR frame of the size the writer was opened with.
  virtual void write(const cv::Mat& frame) = 0;
};

class VideoReader {
 public:
  virtual ~VideoReader() = default;
  /// The next frame (BGR) into `frame`; false at the end.
  virtual bool read(cv::Mat& frame) = 0;
};

/// cv::imread: an empty Mat if the file cannot be read as an image.
[[nodiscard]] cv::Mat read_image(const std::string& path, ImageMode mode);
/// cv::imwrite: false if the image cannot be written there (unknown extension, no such directory).
[[nodiscard]] bool write_image(const std::string& path, const cv::Mat& image);
/// cv::haveImageReader: whether some codec recognises the file's signature.
[[nodiscard]] bool have_image_reader(const std::string& path);
/// A colour video written through FFmpeg (cv::VideoWriter with CAP_FFMPEG); nullptr if it cannot be
/// created there. The codec is fourcc_for(path).
[[nodiscard]] std::unique_ptr<VideoWriter> open_video_writer(const std::string& path, double fps, cv::Size size);
/// cv::VideoCapture(path, CAP_FFMPEG), for references that must be OpenCV's own decoding; nullptr if
/// it cannot open the file.
[[nodiscard]] std::unique_ptr<VideoReader> open_video_reader(const std::string& path);

/// cv::VideoWriter::fourcc.
constexpr int fourcc(char a, char b, char c, char d) {
  return (a & 255) + ((b & 255) << 8) + ((c & 255) << 16) + ((d & 255) << 24);
}
/// Motion JPEG for .avi files (what AVI players expect), MPEG-4 part 2 otherwise (.mp4, .mkv).
[[nodiscard]] int fourcc_for(const std::string& path);

/// Whether this process has loaded the plug-in (for tests and diagnostics).
[[nodiscard]] bool plugin_loaded();

}  // namespace neopipe::pipeline::media
