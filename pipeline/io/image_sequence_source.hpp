#pragma once
// Frames from image files, in the given order.

#include <string>
#include <vector>

#include "pipeline/io/frame_source.hpp"

namespace neopipe::pipeline::io {

class ImageSequenceSource final : public FrameSource {
 public:
  ImageSequenceSource(std::vector<std::string> files, ColorFormat format, std::string description);
  std::optional<SourceFrame> next() override;
  std::string description() const override { return description_; }
  double fps() const override { return 0; }
  std::optional<std::int64_t> frame_count() const override { return static_cast<std::int64_t>(files_.size()); }

 private:
  std::vector<std::string> files_;
  ColorFormat format_;
  std::string description_;
  size_t pos_ = 0;
  cv::Size first_size_;
};

}  // namespace neopipe::pipeline::io
