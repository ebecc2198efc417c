// The Halide peer when this build has no Halide (CMake did not find Halide 14): neopipe bench
// leaves the `halide` implementation out and says so.
#include <stdexcept>

#include "bench/halide_peer.hpp"

namespace neopipe::bench {

struct HalideChain::State {};

bool halide_available() {
  return false;
}

HalideChain::HalideChain(int /*threads*/) {
  throw std::logic_error("this neopipe was built without Halide (install libhalide14-0-dev and rebuild)");
}
HalideChain::~HalideChain() = default;
cv::Mat HalideChain::iconic(const cv::Mat& /*gray*/, int /*threshold*/) {
  return {};
}
void HalideChain::iconic(const cv::Mat& /*gray*/, int /*threshold*/, cv::Mat& /*out*/) {}
pipeline::BlobList HalideChain::operator()(const cv::Mat& /*gray*/, int /*threshold*/) {
  return {};
}
void HalideChain::submit(const cv::Mat& /*gray*/, int /*threshold*/) {}
std::int64_t HalideChain::finish() {
  return 0;
}

}  // namespace neopipe::bench
