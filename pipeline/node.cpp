#include "pipeline/node.hpp"

#include <stdexcept>

namespace neopipe::pipeline {

void Node::begin_frame(NodeIO& io) {
  for (size_t k = 0; k < outputs_.size(); ++k) {
    if (is_image(outputs_[k].type)) io.out_image(k);
  }
}

namespace {

// An input's rows straight from its whole-frame image.
class FrameRows final : public RowInputs {
 public:
  explicit FrameRows(const NodeIO& io) : io_(io) {}
  const std::uint8_t* row(size_t input, int y) const override { return io_.image(input).ptr<std::uint8_t>(y); }

 private:
  const NodeIO& io_;
};

}  // namespace

void Node::run_rows(NodeIO& io, cv::Range rows) const {
  const FrameRows in(io);
  cv::Mat& out = io.out_image(0);
  for (int y = rows.start; y < rows.end; ++y) compute_row(in, out.ptr<std::uint8_t>(y), y, out.cols);
}

void Node::compute_row(const RowInputs& /*in*/, std::uint8_t* /*out*/, int /*y*/, int /*width*/) const {
  throw std::logic_error("this node has no row form (compute_row)");
}

}  // namespace neopipe::pipeline
