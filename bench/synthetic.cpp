#include "bench/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace neopipe::bench {

cv::Mat make_dots_frame(cv::Size size, int count, std::uint64_t seed, double radius) {
  cv::RNG rng(seed);
  cv::Mat f(size, CV_32F);
  // Background: level 40 with a 12-level gradient across the frame.
  for (int y = 0; y < size.height; ++y) {
    auto* row = f.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      row[x] = 40.0F + 12.0F * static_cast<float>(x + y) / static_cast<float>(size.width + size.height);
    }
  }
  const double r = radius > 0 ? radius : std::max(3.0, std::min(size.width, size.height) / 80.0);
  // Centres are binned into square cells as wide as the smallest allowed distance, so a candidate is
  // checked against the centres of the 3x3 cells around it only: the same answer as checking them
  // all, in constant time, which keeps 10,000 disks quick.
  const double gap = 2 * r + 4;
  const int cols = static_cast<int>(size.width / gap) + 1;
  const int rows = static_cast<int>(size.height / gap) + 1;
  std::vector<std::vector<cv::Point2d>> cells(static_cast<size_t>(cols) * static_cast<size_t>(rows));
  const auto cell_of = [&](double v, int n) { return std::clamp(static_cast<int>(v / gap), 0, n - 1); };
  std::vector<cv::Point2d> centres;
  for (int attempt = 0; attempt < count * 200 && static_cast<int>(centres.size()) < count; ++attempt) {
    const cv::Point2d c(rng.uniform(r + 1, size.width - r - 1), rng.uniform(r + 1, size.height - r - 1));
    const int cx = cell_of(c.x, cols);
    const int cy = cell_of(c.y, rows);
    bool clear = true;
    for (int y = std::max(0, cy - 1); clear && y <= std::min(rows - 1, cy + 1); ++y) {
      for (int x = std::max(0, cx - 1); clear && x <= std::min(cols - 1, cx + 1); ++x) {
        const auto& cell = cells[static_cast<size_t>(y) * static_cast<size_t>(cols) + static_cast<size_t>(x)];
        clear = std::all_of(cell.begin(), cell.end(), [&](const cv::Point2d& o) { return cv::norm(o - c) > gap; });
      }
    }
    if (!clear) continue;
    centres.push_back(c);
    cells[static_cast<size_t>(cy) * static_cast<size_t>(cols) + static_cast<size_t>(cx)].push_back(c);
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
