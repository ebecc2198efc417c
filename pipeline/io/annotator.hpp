#pragma once
// Draws each frame's blobs (bounding box in green, intensity-weighted centroid as a red cross) over
// the input frame and writes the result as a video or as PNG/JPEG images.

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>

#include "pipeline/media/media.hpp"
#include "pipeline/value.hpp"

namespace neopipe::pipeline::io {

class Annotator {
 public:
  /// `path`: a video (.mp4, .avi, .mkv) written at `fps`, or an image file (.png, .jpg, ...). For an
  /// image and a stream of several frames, frame k goes to STEM_kkkkkk.EXT; with `single_frame`, the
  /// one frame goes to `path` itself.
  Annotator(std::string path, double fps, bool single_frame);
  /// Throws std::runtime_error naming the file if it cannot be written.
  void write(std::int64_t frame, const cv::Mat& input, const BlobList& blobs);
  /// Finishes the video file.
  void close();

 private:
  std::string path_;
  double fps_;
  bool single_frame_;
  bool video_;
  std::unique_ptr<media::VideoWriter> writer_;
};

/// The annotated picture itself.
cv::Mat draw_blobs(const cv::Mat& input, const BlobList& blobs);

}  // namespace neopipe::pipeline::io
