#include "pipeline/io/video_source.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "pipeline/io/files.hpp"

namespace neopipe::pipeline::io {

VideoSource::VideoSource(std::string path, ColorFormat format) : path_(std::move(path)), format_(format) {
  require_readable(path_);
  if (!cap_.open(path_, cv::CAP_FFMPEG) || !cap_.isOpened()) {
    throw SourceError(path_ + ": neither an image nor a video OpenCV can read");
  }
  fps_ = cap_.get(cv::CAP_PROP_FPS);
  if (!std::isfinite(fps_) || fps_ < 0) fps_ = 0;
  const double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
  declared_frames_ = std::isfinite(n) && n > 0 ? static_cast<std::int64_t>(n) : 0;
  if (!cap_.read(pending_) || pending_.empty()) throw SourceError(path_ + ": the video has no frames");
  size_ = pending_.size();
}

std::optional<std::int64_t> VideoSource::frame_count() const {
  if (declared_frames_ > 0) return declared_frames_;
  return std::nullopt;
}

// Throws if the stream stops short of the frame count its container declares, or changes size.
std::optional<SourceFrame> VideoSource::next() {
  if (ended_) return std::nullopt;
  cv::Mat raw;
  if (!pending_.empty()) {
    raw = std::move(pending_);
    pending_ = cv::Mat();
  } else if (!cap_.read(raw) || raw.empty()) {
    ended_ = true;
    if (declared_frames_ > 0 && pos_ < declared_frames_) {
      throw SourceError(path_ + ": decoding stopped at frame " + std::to_string(pos_) + " of " +
                        std::to_string(declared_frames_) + " (truncated or corrupt video)");
    }
    return std::nullopt;
  }
  if (raw.size() != size_) {
    throw SourceError(path_ + ": frame " + std::to_string(pos_) + " is " + size_text(raw.size()) +
                      " but the video started at " + size_text(size_));
  }
  SourceFrame f;
  f.index = pos_++;
  if (format_ == ColorFormat::gray) {
    cv::cvtColor(raw, f.image, raw.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  } else if (raw.channels() == 1) {
    cv::cvtColor(raw, f.image, cv::COLOR_GRAY2BGR);
  } else {
    f.image = std::move(raw);
  }
  return f;
}

}  // namespace neopipe::pipeline::io
