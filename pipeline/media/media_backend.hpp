#pragma once
// What the media plug-in implements: the image and video codecs neopipe takes from OpenCV's
// imgcodecs and videoio. Only media.cpp (which loads the plug-in) and the plug-in itself include
// this; everything else calls the functions of media.hpp.
//
// The plug-in is built in the same tree with the same compiler and shares libopencv_core with the
// program, so C++ types (cv::Mat, std::string, std::unique_ptr) cross the boundary safely; the
// version number guards against a stale plug-in left in a build directory.

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "pipeline/media/media.hpp"

namespace neopipe::pipeline::media {

/// Bumped whenever MediaBackend, VideoWriter or VideoReader (media.hpp) change.
inline constexpr int kMediaBackendVersion = 1;

/// The name of the plug-in's entry point, declared below.
inline constexpr const char* kMediaBackendEntry = "neopipe_media_backend";

/// No member throws: OpenCV's exceptions are turned into the failure results documented here.
class MediaBackend {
 public:
  virtual ~MediaBackend() = default;
  /// An empty Mat if the file cannot be read as an image.
  [[nodiscard]] virtual cv::Mat read_image(const std::string& path, ImageMode mode) const = 0;
  /// False if the image cannot be written there (unknown extension, directory missing, ...).
  [[nodiscard]] virtual bool write_image(const std::string& path, const cv::Mat& image) const = 0;
  /// Whether some codec recognises the file's signature (cv::haveImageReader).
  [[nodiscard]] virtual bool have_image_reader(const std::string& path) const = 0;
  /// Through FFmpeg; nullptr if the file cannot be created.
  [[nodiscard]] virtual std::unique_ptr<VideoWriter> open_video_writer(const std::string& path, int fourcc, double fps,
                                                                       cv::Size size) const = 0;
  /// cv::VideoCapture(path, CAP_FFMPEG); nullptr if it cannot open the file.
  [[nodiscard]] virtual std::unique_ptr<VideoReader> open_video_reader(const std::string& path) const = 0;
};

}  // namespace neopipe::pipeline::media

/// The plug-in's entry point: its backend, which lives until the process ends, after storing the
/// kMediaBackendVersion it was built with through `version`.
extern "C" const neopipe::pipeline::media::MediaBackend* neopipe_media_backend(int* version);
