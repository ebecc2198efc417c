#include "bench/peers.hpp"

#include <oneapi/tbb/combinable.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace neopipe::bench {

int OpenCvBlobs::operator()(const cv::Mat& gray, int threshold) {
  cv::threshold(gray, binary_, threshold, 255, cv::THRESH_BINARY);
  return cv::connectedComponentsWithStats(binary_, labels_, stats_, centroids_, 8, CV_32S) - 1;
}

namespace {

std::int64_t summed_areas(const cv::Mat& stats) {
  std::int64_t total = 0;
  for (int i = 1; i < stats.rows; ++i) total += stats.at<int>(i, cv::CC_STAT_AREA);  // row 0: background
  return total;
}

}  // namespace

std::int64_t OpenCvBlobs::total_area() const {
  return summed_areas(stats_);
}

OpenCvChain::OpenCvChain() : kernel_(cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3))) {}

int OpenCvChain::operator()(const cv::Mat& gray, int threshold) {
  cv::GaussianBlur(gray, smooth_, cv::Size(3, 3), 0, 0, cv::BORDER_REPLICATE);
  cv::threshold(smooth_, binary_, threshold, 255, cv::THRESH_BINARY);
  cv::morphologyEx(binary_, opened_, cv::MORPH_OPEN, kernel_);
  return cv::connectedComponentsWithStats(opened_, labels_, stats_, centroids_, 8, CV_32S) - 1;
}

std::int64_t OpenCvChain::total_area() const {
  return summed_areas(stats_);
}

struct ReadFloor::Arena {
  explicit Arena(int n) : arena(n) {}
  tbb::task_arena arena;
};

ReadFloor::ReadFloor(int threads) : threads_(threads), arena_(std::make_unique<Arena>(threads)) {}
ReadFloor::~ReadFloor() = default;

std::uint64_t ReadFloor::operator()(const cv::Mat& gray) {
  if (threads_ <= 1) return static_cast<std::uint64_t>(cv::sum(gray)[0]);
  tbb::combinable<std::uint64_t> total([] { return std::uint64_t{0}; });
  const int stripes = threads_ * 4;
  const int rows = (gray.rows + stripes - 1) / stripes;
  arena_->arena.execute([&] {
    tbb::parallel_for(0, stripes, [&](int k) {
      const int y0 = k * rows;
      const int y1 = std::min(gray.rows, y0 + rows);
      if (y0 < y1) total.local() += static_cast<std::uint64_t>(cv::sum(gray.rowRange(y0, y1))[0]);
    });
  });
  return total.combine(std::plus<>());
}

}  // namespace neopipe::bench
