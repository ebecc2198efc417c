// The bench's Halide composite (bench/halide_peer.hpp) against neopipe: its iconic stages against the
// scalar references of smooth, threshold, erode and dilate on random frames (odd sizes, 1-3 rows and
// columns included), and its blob tables against neopipe's chain graph run through the executor.
// Skipped when this build has no Halide.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "bench/blob_bench.hpp"
#include "bench/halide_peer.hpp"
#include "bench/synthetic.hpp"
#include "kernels/reference/reference.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::bench {
namespace {

namespace ref = kernels::reference;

cv::Mat reference_opening(const cv::Mat& gray, int threshold) {
  const cv::Mat smooth = ref::conv3x3(gray, kernels::smooth3x3(), CV_8UC1);
  const cv::Mat binary = ref::threshold(smooth, threshold, 255);
  const cv::Mat eroded = ref::bool3x3(binary, kernels::Bool3x3{kernels::erode_table()});
  return ref::bool3x3(eroded, kernels::Bool3x3{kernels::dilate_table()});
}

// Random gray frames: smoothed noise around the threshold, so every stage has edges to get wrong.
cv::Mat random_frame(std::mt19937& rng, int width, int height) {
  cv::Mat m(height, width, CV_8UC1);
  cv::randu(m, 0, 256);
  std::uniform_int_distribution<int> coin(0, 1);
  if (coin(rng) == 1) cv::blur(m, m, cv::Size(3, 3));
  return m;
}

TEST(HalidePeer, IconicStagesEqualTheScalarReferences) {
  if (!halide_available()) GTEST_SKIP() << "built without Halide";
  std::mt19937 rng(7);
  cv::setRNGSeed(7);
  std::uniform_int_distribution<int> side(1, 97);
  std::uniform_int_distribution<int> level(0, 255);
  HalideChain chain(2);
  int compared = 0;
  for (int i = 0; i < 200; ++i) {
    // Sizes 1-3 every fourth frame, widths across the vector size and strip height otherwise.
    const int w = i % 4 == 0 ? 1 + i % 3 : side(rng);
    const int h = i % 4 == 1 ? 1 + i % 3 : side(rng);
    const cv::Mat gray = random_frame(rng, w, h);
    const int t = i % 5 == 0 ? 0 : level(rng);
    const cv::Mat ours = chain.iconic(gray, t);
    const cv::Mat expected = reference_opening(gray, t);
    ASSERT_EQ(cv::countNonZero(ours != expected), 0) << w << "x" << h << " threshold " << t;
    ++compared;
  }
  EXPECT_EQ(compared, 200);
}

TEST(HalidePeer, IconicStagesReadPaddedRows) {
  if (!halide_available()) GTEST_SKIP() << "built without Halide";
  std::mt19937 rng(3);
  const cv::Mat big = random_frame(rng, 150, 90);
  const cv::Mat roi = big(cv::Rect(7, 5, 101, 61));  // rows longer than the frame: a step of 150
  HalideChain chain(1);
  EXPECT_EQ(cv::countNonZero(chain.iconic(roi, 120) != reference_opening(roi.clone(), 120)), 0);
}

TEST(HalidePeer, CompositeFindsNeopipesChainBlobs) {
  if (!halide_available()) GTEST_SKIP() << "built without Halide";
  const cv::Size size(331, 247);
  std::vector<cv::Mat> frames;
  for (std::uint64_t s = 0; s < 6; ++s) frames.push_back(make_dots_frame(size, 60, 100 + s, 0));
  const auto results =
      pipeline::run_frames(pipeline::compile(chain_graph(dots_threshold), pipeline::standard_kernels()), frames, {});
  std::int64_t total = 0;
  HalideChain one(1);
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto& ours = std::get<pipeline::BlobList>(results[i].outputs[0]);
    const auto theirs = one(frames[i], dots_threshold);
    ASSERT_EQ(ours.size(), theirs.size()) << "frame " << i;
    ASSERT_GT(ours.size(), 0u);
    for (size_t b = 0; b < ours.size(); ++b) {
      EXPECT_EQ(ours[b].area, theirs[b].area);
      EXPECT_EQ(ours[b].x0, theirs[b].x0);
      EXPECT_EQ(ours[b].y0, theirs[b].y0);
      EXPECT_DOUBLE_EQ(ours[b].wcx, theirs[b].wcx);
      EXPECT_DOUBLE_EQ(ours[b].wcy, theirs[b].wcy);
      EXPECT_DOUBLE_EQ(ours[b].mu11, theirs[b].mu11);
    }
    total += static_cast<std::int64_t>(ours.size());
  }
  // Streamed with the blob stage overlapping the next frame's Halide stages: the same count.
  for (const int threads : {1, 2}) {
    HalideChain stream(threads);
    for (int round = 0; round < 3; ++round) {
      for (const auto& f : frames) stream.submit(f, dots_threshold);
    }
    EXPECT_EQ(stream.finish(), 3 * total) << threads << " threads";
  }
}

TEST(HalidePeer, RejectsWhatItCannotRun) {
  if (!halide_available()) GTEST_SKIP() << "built without Halide";
  HalideChain chain(1);
  EXPECT_THROW(chain.iconic(cv::Mat(4, 4, CV_16UC1, cv::Scalar(0)), 10), std::invalid_argument);
  EXPECT_THROW(chain.iconic(cv::Mat(), 10), std::invalid_argument);
  EXPECT_THROW(chain.iconic(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), 256), std::invalid_argument);
  EXPECT_THROW(chain.iconic(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), -1), std::invalid_argument);
}

}  // namespace
}  // namespace neopipe::bench
