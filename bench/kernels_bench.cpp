// Kernel micro-benchmarks, each beside the OpenCV call that computes the same thing, at 640x480.
//   ./build/bench/neopipe_kernels_bench --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/synthetic.hpp"
#include "kernels/alu.hpp"
#include "kernels/blobs.hpp"
#include "kernels/bool3x3.hpp"
#include "kernels/conv3x3.hpp"
#include "kernels/histogram.hpp"
#include "kernels/lut.hpp"
#include "kernels/threshold.hpp"

namespace {
namespace k = neopipe::kernels;

const cv::Mat& frame() {
  static const cv::Mat f = neopipe::bench::make_dots_frame({640, 480}, 100, 7);
  return f;
}
const cv::Mat& binary() {
  static const cv::Mat b = [] {
    cv::Mat out;
    cv::threshold(frame(), out, neopipe::bench::dots_threshold, 255, cv::THRESH_BINARY);
    return out;
  }();
  return b;
}

void set_bytes(benchmark::State& s) {
  s.SetBytesProcessed(static_cast<int64_t>(s.iterations()) * frame().total());
}

void BM_lut_neopipe(benchmark::State& s) {
  cv::Mat out;
  k::Lut t = k::identity_lut();
  for (auto& v : t) v = static_cast<std::uint8_t>(255 - v);
  for (auto _ : s) k::lut(frame(), out, t);
  set_bytes(s);
}
void BM_lut_opencv(benchmark::State& s) {
  cv::Mat out;
  cv::Mat t(1, 256, CV_8U);
  for (int i = 0; i < 256; ++i) t.at<std::uint8_t>(i) = static_cast<std::uint8_t>(255 - i);
  for (auto _ : s) cv::LUT(frame(), t, out);
  set_bytes(s);
}
void BM_threshold_neopipe(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) k::threshold(frame(), out, 128);
  set_bytes(s);
}
void BM_threshold_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::threshold(frame(), out, 128, 255, cv::THRESH_BINARY);
  set_bytes(s);
}
void BM_absdiff_neopipe(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) k::alu(k::AluOp::absdiff, frame(), binary(), out);
  set_bytes(s);
}
void BM_absdiff_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::absdiff(frame(), binary(), out);
  set_bytes(s);
}
void BM_smooth3x3_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Conv3x3 c = k::smooth3x3();
  for (auto _ : s) k::conv3x3(frame(), out, c);
  set_bytes(s);
}
void BM_smooth3x3_opencv(benchmark::State& s) {
  cv::Mat out;
  const cv::Mat kernel = (cv::Mat_<float>(3, 3) << 1, 2, 1, 2, 4, 2, 1, 2, 1) / 16.0;
  for (auto _ : s) cv::filter2D(frame(), out, CV_8U, kernel, {-1, -1}, 0, cv::BORDER_REPLICATE);
  set_bytes(s);
}
void BM_erode_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Bool3x3 e{k::erode_table(), 255, {}};
  for (auto _ : s) k::bool3x3(binary(), out, e);
  set_bytes(s);
}
void BM_erode_opencv(benchmark::State& s) {
  cv::Mat out;
  const cv::Mat se = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
  for (auto _ : s) cv::erode(binary(), out, se);
  set_bytes(s);
}
void BM_histogram_neopipe(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(k::histogram(frame()));
  set_bytes(s);
}
void BM_histogram_opencv(benchmark::State& s) {
  cv::Mat hist;
  const int channels = 0;
  const int bins = 256;
  const float range[] = {0, 256};
  const float* ranges = range;
  for (auto _ : s) cv::calcHist(&frame(), 1, &channels, cv::Mat(), hist, 1, &bins, &ranges);
  set_bytes(s);
}
void BM_blobs_neopipe(benchmark::State& s) {
  for (auto _ : s) benchmark::DoNotOptimize(k::extract_blobs(frame(), {128, k::Connectivity::eight}));
  set_bytes(s);
}
void BM_blobs_opencv(benchmark::State& s) {
  cv::Mat bin;
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  for (auto _ : s) {
    cv::threshold(frame(), bin, 128, 255, cv::THRESH_BINARY);
    cv::connectedComponentsWithStats(bin, labels, stats, centroids, 8, CV_32S);
  }
  set_bytes(s);
}

BENCHMARK(BM_lut_neopipe);
BENCHMARK(BM_lut_opencv);
BENCHMARK(BM_threshold_neopipe);
BENCHMARK(BM_threshold_opencv);
BENCHMARK(BM_absdiff_neopipe);
BENCHMARK(BM_absdiff_opencv);
BENCHMARK(BM_smooth3x3_neopipe);
BENCHMARK(BM_smooth3x3_opencv);
BENCHMARK(BM_erode_neopipe);
BENCHMARK(BM_erode_opencv);
BENCHMARK(BM_histogram_neopipe);
BENCHMARK(BM_histogram_opencv);
BENCHMARK(BM_blobs_neopipe);
BENCHMARK(BM_blobs_opencv);

}  // namespace

BENCHMARK_MAIN();
