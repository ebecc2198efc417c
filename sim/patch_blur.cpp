#include "sim/patch_blur.hpp"

#include <cmath>

namespace neopipe::sim {

PatchBlur::PatchBlur(double sigma)
    : radius_(static_cast<int>(std::ceil(4 * sigma))), kernel_(2 * static_cast<std::size_t>(radius_) + 1) {
  double sum = 0;
  std::vector<double> k(kernel_.size());
  for (std::size_t j = 0; j < k.size(); ++j) {
    const double i = static_cast<double>(j) - radius_;  // taps -radius .. radius
    k[j] = std::exp(-0.5 * i * i / (sigma * sigma));
    sum += k[j];
  }
  for (std::size_t i = 0; i < k.size(); ++i) kernel_[i] = static_cast<float>(k[i] / sum);
}

void PatchBlur::apply(cv::Mat& patch) const {
  CV_Assert(patch.type() == CV_32F && patch.isContinuous());
  const int w = patch.cols;
  const int h = patch.rows;
  const int r = radius_;
  // Padded copy, so both passes read without bounds checks: zeros are the image beyond the patch.
  cv::Mat padded = cv::Mat::zeros(h + 2 * r, w + 2 * r, CV_32F);
  patch.copyTo(padded(cv::Rect(r, r, w, h)));
  cv::Mat across = cv::Mat::zeros(h + 2 * r, w, CV_32F);
  const float* k = kernel_.data();
  for (int y = r; y < h + r; ++y) {  // rows outside the patch are 0 and stay 0
    const auto* in = padded.ptr<float>(y);
    auto* out = across.ptr<float>(y);
    for (int t = 0; t <= 2 * r; ++t) {
      const float kt = k[t];
      for (int x = 0; x < w; ++x) out[x] += kt * in[x + t];
    }
  }
  for (int y = 0; y < h; ++y) {
    auto* out = patch.ptr<float>(y);
    for (int x = 0; x < w; ++x) out[x] = 0;
    for (int t = 0; t <= 2 * r; ++t) {
      const float kt = k[t];
      const auto* in = across.ptr<float>(y + t);
      for (int x = 0; x < w; ++x) out[x] += kt * in[x];
    }
  }
}

}  // namespace neopipe::sim
