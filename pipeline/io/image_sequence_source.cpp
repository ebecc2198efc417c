#include "pipeline/io/image_sequence_source.hpp"

#include <opencv2/imgproc.hpp>

#include "pipeline/io/files.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::pipeline::io {

ImageSequenceSource::ImageSequenceSource(std::vector<std::string> files, ColorFormat format, std::string description)
    : files_(std::move(files)), format_(format), description_(std::move(description)) {}

std::optional<SourceFrame> ImageSequenceSource::next() {
  if (pos_ >= files_.size()) return std::nullopt;
  const std::string& path = files_[pos_];
  require_readable(path);
  // Always decoded to BGR: IMREAD_GRAYSCALE would use each codec's own luma arithmetic, and gray
  // frames must be BT.601 exactly as cv::cvtColor (and the video source, and the gray kernel) make them.
  cv::Mat img = media::read_image(path, media::ImageMode::color);
  if (img.empty()) throw SourceError(path + ": not an image OpenCV can read (unknown format or corrupt file)");
  if (format_ == ColorFormat::gray) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  if (first_size_.area() == 0) {
    first_size_ = img.size();
  } else if (img.size() != first_size_) {
    throw SourceError(path + ": the image is " + size_text(img.size()) + " but the sequence started at " +
                      size_text(first_size_) + " (" + files_.front() + ")");
  }
  return SourceFrame{static_cast<std::int64_t>(pos_++), std::move(img)};
}

}  // namespace neopipe::pipeline::io
