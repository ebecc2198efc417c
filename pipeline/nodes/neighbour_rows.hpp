#pragma once
// The rows above and below an output row, for 3x3 nodes computing one row at a time: inside the
// frame they come from the input, outside it from the node's vertical border.

#include <algorithm>
#include <cstdint>
#include <opencv2/core/types.hpp>
#include <vector>

#include "kernels/types.hpp"
#include "pipeline/node.hpp"

namespace neopipe::pipeline::nodes {

struct Neighbours {
  const std::uint8_t* up;
  const std::uint8_t* mid;
  const std::uint8_t* down;
};

class VerticalBorder {
 public:
  /// `constant_fill` is the byte a constant border row holds.
  VerticalBorder(kernels::Border border, std::uint8_t constant_fill) : border_(border), fill_(constant_fill) {}

  void configure(cv::Size frame) {
    height_ = frame.height;
    if (border_.mode == kernels::BorderMode::constant) constant_row_.assign(static_cast<size_t>(frame.width), fill_);
  }

  Neighbours rows(const RowInputs& in, size_t input, int y) const {
    return {row(in, input, y - 1), in.row(input, y), row(in, input, y + 1)};
  }

 private:
  const std::uint8_t* row(const RowInputs& in, size_t input, int y) const {
    if (y >= 0 && y < height_) return in.row(input, y);
    if (border_.mode == kernels::BorderMode::constant) return constant_row_.data();
    return in.row(input, std::clamp(y, 0, height_ - 1));
  }

  kernels::Border border_;
  std::uint8_t fill_;
  int height_ = 0;
  std::vector<std::uint8_t> constant_row_;
};

}  // namespace neopipe::pipeline::nodes
