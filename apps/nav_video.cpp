#include "apps/nav_video.hpp"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace neopipe::apps {

NavVideo::NavVideo(std::string path, double window_side, int side_px)
    : path_(std::move(path)), side_(window_side), side_px_(side_px) {
  const bool avi = path_.ends_with(".avi");
  if (!avi && !path_.ends_with(".mp4") && !path_.ends_with(".mkv")) {
    throw std::runtime_error(fmt::format("--video {}: the video must be a .mp4, .avi or .mkv file", path_));
  }
  writer_ = pipeline::media::open_video_writer(path_, 30, cv::Size(side_px_, side_px_));
  if (!writer_) {
    throw std::runtime_error(fmt::format("--video {}: cannot write a video there", path_));
  }
}

cv::Point NavVideo::to_pixel(const Eigen::Vector2d& p) const {
  // Window x runs along image x; window y (North) runs up the image.
  const double scale = side_px_ / side_;
  return {static_cast<int>(std::lround(p.x() * scale)), static_cast<int>(std::lround(side_px_ - p.y() * scale))};
}

void NavVideo::landmark_held(std::size_t entry, const Eigen::Vector2d& window_position) {
  held_ = window_position;
  entry_ = entry;
}

void NavVideo::frame_seen(const pipeline::io::SourceFrame& frame, const nav::navigator::Sighting& sighting) {
  cv::Mat bgr;
  if (frame.image.channels() == 1) {
    cv::cvtColor(frame.image, bgr, cv::COLOR_GRAY2BGR);
  } else {
    bgr = frame.image.clone();
  }
  for (const Eigen::Vector2d& p : sighting.objects)
    cv::circle(bgr, to_pixel(p), 9, cv::Scalar(0, 200, 0), 1, cv::LINE_AA);
  if (held_) {
    cv::drawMarker(bgr, to_pixel(*held_), cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 18, 2, cv::LINE_AA);
    cv::putText(bgr, fmt::format("entry {}", entry_), {6, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 255), 1,
                cv::LINE_AA);
  }
  cv::putText(bgr, fmt::format("frame {}", frame.index), {6, side_px_ - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  writer_->write(bgr);
  ++frames_;
  // A held mark belongs to the frame it was held in; later frames show the next look.
  held_.reset();
}

void NavVideo::close() {
  writer_.reset();  // finishes the file
  if (frames_ == 0) throw std::runtime_error(fmt::format("--video {}: the journey produced no frames", path_));
}

}  // namespace neopipe::apps
