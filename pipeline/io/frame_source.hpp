#pragma once
// Where frames come from: a video file, or a sequence of image files (given one by one or as a
// directory). Every failure is a SourceError whose message names the input and the cause, in one
// line.

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace neopipe::pipeline::io {

class SourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The pixel format the graph's source wants; the reader converts to it (BT.601 for gray).
enum class ColorFormat { bgr, gray };

struct SourceFrame {
  std::int64_t index = 0;  ///< 0, 1, 2, ... in stream order
  cv::Mat image;           ///< freshly allocated for every frame
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  /// The next frame, or nullopt after the last. Throws SourceError.
  virtual std::optional<SourceFrame> next() = 0;
  /// For messages: the file, or "N images from DIR".
  virtual std::string description() const = 0;
  /// Frames per second of a video; 0 when the source has no rate (images).
  virtual double fps() const = 0;
  /// The number of frames, when known in advance.
  virtual std::optional<std::int64_t> frame_count() const = 0;
};

/// Opens `inputs`: one video file, or any number of image files and directories of images (taken in
/// name order). Throws SourceError for a missing or unreadable path, a file that is neither an
/// image nor a video, an empty directory or video, or a mix of videos and images.
std::unique_ptr<FrameSource> open_frame_source(const std::vector<std::string>& inputs, ColorFormat format);

/// True for the file name extensions neopipe treats as images when scanning a directory.
bool has_image_extension(const std::string& path);

/// Whether open_frame_source reads the regular file `path` as an image (else as a video): by its
/// signature, as cv::haveImageReader decides, but without loading OpenCV's codecs for a video.
bool is_image_file(const std::string& path);

}  // namespace neopipe::pipeline::io
