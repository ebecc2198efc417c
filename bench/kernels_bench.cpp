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
#include "kernels/convert.hpp"
#include "kernels/gray.hpp"
#include "kernels/histogram.hpp"
#include "kernels/lut.hpp"
#include "kernels/lut2.hpp"
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

// Random colours rather than a gray frame in three channels, so nothing can shortcut B == G == R.
const cv::Mat& colour() {
  static const cv::Mat c = [] {
    cv::Mat out(frame().size(), CV_8UC3);
    cv::RNG rng(11);
    rng.fill(out, cv::RNG::UNIFORM, 0, 256);
    return out;
  }();
  return c;
}
const cv::Mat& sobel_x_s16() {
  static const cv::Mat g = [] {
    cv::Mat out;
    cv::Sobel(frame(), out, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
    return out;
  }();
  return g;
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
void BM_alu_neopipe(benchmark::State& s, k::AluOp op) {
  cv::Mat out;
  for (auto _ : s) k::alu(op, frame(), binary(), out);
  set_bytes(s);
}
void BM_add_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::add(frame(), binary(), out);
  set_bytes(s);
}
void BM_sub_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::subtract(frame(), binary(), out);
  set_bytes(s);
}
void BM_min_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::min(frame(), binary(), out);
  set_bytes(s);
}
void BM_and_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::bitwise_and(frame(), binary(), out);
  set_bytes(s);
}
void BM_lut2_neopipe(benchmark::State& s) {
  cv::Mat out;
  const auto t = k::Lut2::from_function([](int a, int b) { return static_cast<std::uint8_t>((3 * a + b + 2) / 4); });
  for (auto _ : s) k::lut2(frame(), binary(), out, t);
  set_bytes(s);
}
// The nearest OpenCV call to the running-average table (not bit-identical: different rounding).
void BM_lut2_opencv_addweighted(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::addWeighted(frame(), 0.75, binary(), 0.25, 0.5, out);
  set_bytes(s);
}
void BM_gray_neopipe(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) k::bgr_to_gray(colour(), out);
  set_bytes(s);
}
void BM_gray_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::cvtColor(colour(), out, cv::COLOR_BGR2GRAY);
  set_bytes(s);
}
void BM_convert_neopipe(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) k::convert_s16(sobel_x_s16(), out, {true, 2});
  set_bytes(s);
}
// Same work; OpenCV rounds halves to even, so the results differ slightly.
void BM_convert_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::convertScaleAbs(sobel_x_s16(), out, 0.25);
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
void BM_sobel_x_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Conv3x3 c = k::sobel_x3x3();
  for (auto _ : s) k::conv3x3(frame(), out, c, CV_16SC1);
  set_bytes(s);
}
void BM_sobel_x_opencv(benchmark::State& s) {
  cv::Mat out;
  for (auto _ : s) cv::Sobel(frame(), out, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
  set_bytes(s);
}
// Weights too large for 16-bit sums: the general (32-bit) path.
void BM_conv3x3_wide_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Conv3x3 c{{300, -1000, 2000, 4000, 9000, 4000, 2000, -1000, 300}, 15, {}};
  for (auto _ : s) k::conv3x3(frame(), out, c);
  set_bytes(s);
}
void BM_conv3x3_wide_opencv(benchmark::State& s) {
  cv::Mat out;
  const cv::Mat kernel = (cv::Mat_<float>(3, 3) << 300, -1000, 2000, 4000, 9000, 4000, 2000, -1000, 300) / 32768.0;
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
void BM_dilate_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Bool3x3 e{k::dilate_table(), 255, {}};
  for (auto _ : s) k::bool3x3(binary(), out, e);
  set_bytes(s);
}
void BM_dilate_opencv(benchmark::State& s) {
  cv::Mat out;
  const cv::Mat se = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
  for (auto _ : s) cv::dilate(binary(), out, se);
  set_bytes(s);
}
void BM_hitmiss_neopipe(benchmark::State& s) {
  cv::Mat out;
  const k::Bool3x3 e{k::hit_or_miss_table("000 x1x 111"), 255, {}};
  for (auto _ : s) k::bool3x3(binary(), out, e);
  set_bytes(s);
}
void BM_hitmiss_opencv(benchmark::State& s) {
  cv::Mat out;
  const cv::Mat kernel = (cv::Mat_<int>(3, 3) << -1, -1, -1, 0, 1, 0, 1, 1, 1);
  for (auto _ : s) cv::morphologyEx(binary(), out, cv::MORPH_HITMISS, kernel);
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
BENCHMARK_CAPTURE(BM_alu_neopipe, add, k::AluOp::add);
BENCHMARK(BM_add_opencv);
BENCHMARK_CAPTURE(BM_alu_neopipe, sub, k::AluOp::sub);
BENCHMARK(BM_sub_opencv);
BENCHMARK_CAPTURE(BM_alu_neopipe, min, k::AluOp::min);
BENCHMARK(BM_min_opencv);
BENCHMARK_CAPTURE(BM_alu_neopipe, and, k::AluOp::bit_and);
BENCHMARK(BM_and_opencv);
BENCHMARK(BM_lut2_neopipe);
BENCHMARK(BM_lut2_opencv_addweighted);
BENCHMARK(BM_gray_neopipe);
BENCHMARK(BM_gray_opencv);
BENCHMARK(BM_convert_neopipe);
BENCHMARK(BM_convert_opencv);
BENCHMARK(BM_smooth3x3_neopipe);
BENCHMARK(BM_smooth3x3_opencv);
BENCHMARK(BM_sobel_x_neopipe);
BENCHMARK(BM_sobel_x_opencv);
BENCHMARK(BM_conv3x3_wide_neopipe);
BENCHMARK(BM_conv3x3_wide_opencv);
BENCHMARK(BM_erode_neopipe);
BENCHMARK(BM_erode_opencv);
BENCHMARK(BM_dilate_neopipe);
BENCHMARK(BM_dilate_opencv);
BENCHMARK(BM_hitmiss_neopipe);
BENCHMARK(BM_hitmiss_opencv);
BENCHMARK(BM_histogram_neopipe);
BENCHMARK(BM_histogram_opencv);
BENCHMARK(BM_blobs_neopipe);
BENCHMARK(BM_blobs_opencv);

}  // namespace

BENCHMARK_MAIN();
