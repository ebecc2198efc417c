#include "bench/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace neopipe::bench {

cv::Mat make_dots_frame(cv::Size size, int count, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat f(size, CV_32F);
  // Background: level 40 with a 12-level gradient across the frame.
  for (int y = 0; y < size.height; ++y) {
    auto* row = f.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      row[x] = 40.0F + 12.0F * static_cast<float>(x + y) / static_cast<float>(size.width + size.height);
    }
  }
  const double r = std::max(3.0, std::min(size.width, size.height) / 80.0);
  std::vector<cv::Point2d> centres;
  for (int attempt = 0; attempt < count * 200 && static_cast<int>(centres.size()) < count; ++attempt) {
    const cv::Point2d c(rng.uniform(r + 1, size.width - r - 1), rng.uniform(r + 1, size.height - r - 1));
    const bool clear =
        std::all_of(centres.begin(), centres.end(), [&](const cv::Point2d& o) { return cv::norm(o - c) > 2 * r + 4; });
    if (clear) centres.push_back(c);
  }
  for (const auto& c : centres) {
    const int x0 = std::max(0, static_cast<int>(c.x - r - 1));
    const int x1 = std::min(size.width - 1, static_cast<int>(c.x + r + 1));
    const int y0 = std::max(0, static_cast<int>(c.y - r - 1));
    const int y1 = std::min(size.height - 1, static_cast<int>(c.y + r + 1));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double d = std::hypot(x - c.x, y - c.y);
        // Coverage of a pixel by the disk's edge, and a spherical shading inside it.
        const double cover = std::clamp(r + 0.5 - d, 0.0, 1.0);
        if (cover <= 0) continue;
        const double shade = 170.0 + 80.0 * std::sqrt(std::max(0.0, 1.0 - (d * d) / (r * r)));
        float& p = f.at<float>(y, x);
        p = static_cast<float>(p * (1 - cover) + shade * cover);
      }
    }
  }
  cv::Mat noise(size, CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 6.0);
  f += noise;
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

cv::Mat make_dense_frame(cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat noise(size, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  const double sigma = std::max(2.0, std::min(size.width, size.height) / 100.0);
  cv::GaussianBlur(noise, noise, cv::Size(), sigma);
  cv::Mat out;
  cv::normalize(noise, out, 0, 255, cv::NORM_MINMAX, CV_8U);
  return out;
}

int dense_threshold(const cv::Mat& frame) {
  return static_cast<int>(cv::mean(frame)[0]);
}

}  // namespace neopipe::bench
