#pragma once
// Frames from a video file through OpenCV's FFmpeg backend.

#include <opencv2/videoio.hpp>
#include <string>

#include "pipeline/io/frame_source.hpp"

namespace neopipe::pipeline::io {

class VideoSource final : public FrameSource {
 public:
  /// Throws SourceError if the file cannot be opened as a video or holds no frames.
  VideoSource(std::string path, ColorFormat format);
  std::optional<SourceFrame> next() override;
  std::string description() const override { return path_; }
  double fps() const override { return fps_; }
  std::optional<std::int64_t> frame_count() const override;

 private:
  std::string path_;
  ColorFormat format_;
  cv::VideoCapture cap_;
  double fps_ = 0;
  std::int64_t declared_frames_ = 0;  // what the container says; 0 if it does not say
  std::int64_t pos_ = 0;
  cv::Mat pending_;  // the first frame, read at open to prove the file decodes
  bool ended_ = false;
  cv::Size size_;
};

}  // namespace neopipe::pipeline::io
