#include "sim/defocus.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace neopipe::sim {

DefocusBlur::DefocusBlur(const Defocus& d, cv::Size size)
    : defocus_(d), size_(size), half_diagonal2_((size.width * size.width + size.height * size.height) / 4.0) {
  const double lo = std::min(d.centre, d.corner);
  const double hi = std::max(d.centre, d.corner);
  if (hi <= 0) return;
  const int n = static_cast<int>(std::ceil((hi - lo) / step_)) + 1;
  for (int i = 0; i < n; ++i) bank_.emplace_back(std::max(lo + i * step_, 1e-3));
}

double DefocusBlur::sigma(double u, double v) const {
  const double du = u - (size_.width - 1) / 2.0;
  const double dv = v - (size_.height - 1) / 2.0;
  const double rho2 = std::min(1.0, (du * du + dv * dv) / half_diagonal2_);
  return defocus_.centre + (defocus_.corner - defocus_.centre) * rho2;
}

void DefocusBlur::blur_patch(cv::Mat& patch, double u, double v) const {
  if (bank_.empty()) return;
  const double lo = std::min(defocus_.centre, defocus_.corner);
  const auto i = static_cast<std::size_t>(
      std::clamp(std::lround((sigma(u, v) - lo) / step_), 0L, static_cast<long>(bank_.size()) - 1));
  bank_[i].apply(patch);
}

int DefocusBlur::reach() const {
  int r = 0;
  for (const auto& b : bank_) r = std::max(r, b.radius());
  return r;
}

cv::Mat DefocusBlur::blur_frame(const cv::Mat& frame) const {
  const auto gauss = [&](double s) {
    cv::Mat out;
    if (s <= 0) return frame.clone();
    cv::GaussianBlur(frame, out, cv::Size(0, 0), s, s, cv::BORDER_REPLICATE);
    return out;
  };
  if (defocus_.corner == defocus_.centre) return gauss(defocus_.centre);
  // Levels a quarter of the range apart: blending neighbours of a Gaussian family this close is
  // within a fraction of a gray level of the exact kernel at edges (and exact on flat areas).
  constexpr int kLevels = 5;
  std::vector<cv::Mat> levels;
  std::vector<double> sigmas;
  for (int i = 0; i < kLevels; ++i) {
    sigmas.push_back(defocus_.centre + (defocus_.corner - defocus_.centre) * i / (kLevels - 1));
    levels.push_back(gauss(sigmas.back()));
  }
  cv::Mat out(frame.size(), CV_32F);
  for (int y = 0; y < frame.rows; ++y) {
    auto* o = out.ptr<float>(y);
    for (int x = 0; x < frame.cols; ++x) {
      // Position along the levels: sigma is linear in rho^2, so is the level index.
      const double t = (sigma(x, y) - defocus_.centre) / (defocus_.corner - defocus_.centre) * (kLevels - 1);
      const int i = std::clamp(static_cast<int>(t), 0, kLevels - 2);
      const auto f = static_cast<float>(t - i);
      const float a = levels[static_cast<std::size_t>(i)].at<float>(y, x);
      const float b = levels[static_cast<std::size_t>(i) + 1].at<float>(y, x);
      o[x] = a + f * (b - a);
    }
  }
  return out;
}

}  // namespace neopipe::sim
