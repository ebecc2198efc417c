#include "pipeline/io/annotator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "pipeline/io/frame_source.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::pipeline::io {
namespace fs = std::filesystem;

cv::Mat draw_blobs(const cv::Mat& input, const BlobList& blobs) {
  cv::Mat out;
  if (input.channels() == 1) {
    cv::cvtColor(input, out, cv::COLOR_GRAY2BGR);
  } else {
    out = input.clone();
  }
  const int t = std::max(1, out.cols / 640);
  const int arm = 4 * t;
  for (const auto& b : blobs) {
    cv::rectangle(out, cv::Rect(b.x0, b.y0, b.width, b.height), cv::Scalar(0, 200, 0), t);
    // Drawn with 4 bits of sub-pixel precision, so the cross sits where the centroid is.
    constexpr int kShift = 4;
    const auto fx = static_cast<int>(std::lround(b.wcx * (1 << kShift)));
    const auto fy = static_cast<int>(std::lround(b.wcy * (1 << kShift)));
    const int a = arm << kShift;
    cv::line(out, {fx - a, fy}, {fx + a, fy}, cv::Scalar(0, 0, 255), t, cv::LINE_AA, kShift);
    cv::line(out, {fx, fy - a}, {fx, fy + a}, cv::Scalar(0, 0, 255), t, cv::LINE_AA, kShift);
  }
  return out;
}

Annotator::Annotator(std::string path, double fps, bool single_frame)
    : path_(std::move(path)),
      fps_(fps > 0 ? fps : 30),
      single_frame_(single_frame),
      video_(!has_image_extension(path_)) {
  const std::string ext = fs::path(path_).extension().string();
  if (video_ && ext != ".mp4" && ext != ".avi" && ext != ".mkv" && ext != ".mov") {
    throw std::runtime_error(path_ +
                             ": --annotate writes a video (.mp4, .avi, .mkv, .mov) or images (.png, .jpg, ...)");
  }
}

void Annotator::write(std::int64_t frame, const cv::Mat& input, const BlobList& blobs) {
  const cv::Mat img = draw_blobs(input, blobs);
  if (!video_) {
    std::string target = path_;
    if (!single_frame_) {
      const fs::path p(path_);
      target =
          (p.parent_path() / fmt::format("{}_{:06d}{}", p.stem().string(), frame, p.extension().string())).string();
    }
    if (!media::write_image(target, img)) throw std::runtime_error(target + ": cannot write the annotated image");
    return;
  }
  if (!writer_) {
    writer_ = media::open_video_writer(path_, fps_, img.size());
    if (!writer_) throw std::runtime_error(path_ + ": cannot create the annotated video");
  }
  writer_->write(img);
}

void Annotator::close() {
  writer_.reset();
}

}  // namespace neopipe::pipeline::io
