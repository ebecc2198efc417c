// Blob extraction (kernels/blobs.hpp). extract_blobs is held to cv::connectedComponentsWithStats
// (count, areas, bounding boxes, centroids, label image) on random binary images of several sizes
// and densities under 4- and 8-connectivity; its second central moments to cv::moments of each
// component's mask; its intensity-weighted centroids to the scalar reference. OpenCV numbers its
// labels in its own order, so its components are renumbered by their first pixel in raster order,
// the order neopipe promises. Shapes that stress run merging (U, spiral, staircases, combs,
// checkerboards, frame-touching components), thresholds -1 and 255, weights, ROI views, argument
// errors and BlobMoments merging are covered too.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "kernels/blobs.hpp"
#include "kernels/reference/reference.hpp"

namespace k = neopipe::kernels;
namespace ref = neopipe::kernels::reference;
using neopipe::kernels::testing::checkerboard;
using neopipe::kernels::testing::comb;
using neopipe::kernels::testing::describe;
using neopipe::kernels::testing::edge_blobs;
using neopipe::kernels::testing::frame_touching;
using neopipe::kernels::testing::identical_blobs;
using neopipe::kernels::testing::opencv_components;
using neopipe::kernels::testing::OpenCvComponents;
using neopipe::kernels::testing::random_binary;
using neopipe::kernels::testing::same_geometry;
using neopipe::kernels::testing::spiral;
using neopipe::kernels::testing::staircases;
using neopipe::kernels::testing::u_shape;
using neopipe::kernels::testing::wide_staircase;

namespace {

constexpr std::uint64_t kSeed = 0x5eed'0003;
constexpr double kRelativeTolerance = 1e-9;

constexpr k::Connectivity kBothConnectivities[] = {k::Connectivity::four, k::Connectivity::eight};

// ---------------------------------------------------------------------------------------------
// Images

cv::Mat random_gray(cv::RNG& rng, cv::Size size) {
  cv::Mat m(size, CV_8UC1);
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

std::string size_name(const cv::Mat& m) {
  return std::to_string(m.cols) + "x" + std::to_string(m.rows);
}

std::string conn_name(k::Connectivity c) {
  return c == k::Connectivity::four ? "4-connected" : "8-connected";
}

k::BlobParams params(int threshold, k::Connectivity c) {
  return {threshold, c};
}

// ---------------------------------------------------------------------------------------------
// Comparisons

bool close_relative(double actual, double expected) {
  return std::abs(actual - expected) <= kRelativeTolerance * std::max(1.0, std::abs(expected));
}

/// Every field, the floating-point ones to a relative 1e-9.
::testing::AssertionResult same_blob(const k::Blob& a, const k::Blob& e) {
  if (same_geometry(a, e) && close_relative(a.wcx, e.wcx) && close_relative(a.wcy, e.wcy) &&
      close_relative(a.mu20, e.mu20) && close_relative(a.mu11, e.mu11) && close_relative(a.mu02, e.mu02)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "actual " << describe(a) << "\nexpected " << describe(e);
}

::testing::AssertionResult same_labels(const cv::Mat& actual, const cv::Mat& expected) {
  if (actual.size() != expected.size() || actual.type() != expected.type()) {
    return ::testing::AssertionFailure() << "label image is " << size_name(actual) << " "
                                         << cv::typeToString(actual.type()) << ", expected " << size_name(expected)
                                         << " " << cv::typeToString(expected.type());
  }
  for (int y = 0; y < actual.rows; ++y) {
    for (int x = 0; x < actual.cols; ++x) {
      if (actual.at<int>(y, x) != expected.at<int>(y, x)) {
        return ::testing::AssertionFailure() << "label at (" << x << ", " << y << ") is " << actual.at<int>(y, x)
                                             << ", expected " << expected.at<int>(y, x);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

/// mu20, mu11, mu02 of each blob against cv::moments of its mask, cut out of the label image.
::testing::AssertionResult moments_match_opencv(const std::vector<k::Blob>& blobs, const cv::Mat& labels) {
  for (size_t i = 0; i < blobs.size(); ++i) {
    const k::Blob& b = blobs[i];
    const cv::Mat mask = labels(cv::Rect(b.x0, b.y0, b.width, b.height)) == static_cast<int>(i + 1);
    const cv::Moments m = cv::moments(mask, true);
    if (!close_relative(b.mu20, m.mu20) || !close_relative(b.mu11, m.mu11) || !close_relative(b.mu02, m.mu02)) {
      std::ostringstream s;
      s.precision(17);
      s << "blob " << i << " " << describe(b) << ": cv::moments gives mu20 " << m.mu20 << ", mu11 " << m.mu11
        << ", mu02 " << m.mu02;
      return ::testing::AssertionFailure() << s.str();
    }
  }
  return ::testing::AssertionSuccess();
}

/// extract_blobs against OpenCV: count, order, areas, boxes, centroids, the label image and the
/// second moments. Also checks that asking for the label image does not change the blobs.
void expect_blobs_match_opencv(const cv::Mat& src, const k::BlobParams& p) {
  SCOPED_TRACE(size_name(src) + ", threshold " + std::to_string(p.threshold) + ", " + conn_name(p.connectivity));
  cv::Mat labels;
  const auto blobs = k::extract_blobs(src, p, cv::Mat(), &labels);
  const OpenCvComponents e = opencv_components(src, p.threshold, p.connectivity);
  ASSERT_EQ(blobs.size(), e.blobs.size());
  for (size_t i = 0; i < blobs.size(); ++i) ASSERT_TRUE(same_geometry(blobs[i], e.blobs[i])) << "blob " << i;
  ASSERT_TRUE(same_labels(labels, e.labels));
  EXPECT_TRUE(moments_match_opencv(blobs, labels));
  EXPECT_TRUE(identical_blobs(k::extract_blobs(src, p), blobs)) << "without a label image";
}

/// extract_blobs against the reference flood fill: every field, in the same order.
void expect_blobs_match_reference(const cv::Mat& src, const k::BlobParams& p, const cv::Mat& weights = cv::Mat()) {
  SCOPED_TRACE(size_name(src) + ", threshold " + std::to_string(p.threshold) + ", " + conn_name(p.connectivity) +
               (weights.empty() ? "" : ", separate weights"));
  const auto blobs = k::extract_blobs(src, p, weights);
  const auto expected = ref::blobs(src, p, weights);
  ASSERT_EQ(blobs.size(), expected.size());
  for (size_t i = 0; i < blobs.size(); ++i) ASSERT_TRUE(same_blob(blobs[i], expected[i])) << "blob " << i;
}

void expect_blobs_match_both(const cv::Mat& src, const k::BlobParams& p) {
  expect_blobs_match_opencv(src, p);
  expect_blobs_match_reference(src, p);
}

int count_blobs(const cv::Mat& src, k::Connectivity c) {
  return static_cast<int>(k::extract_blobs(src, params(0, c)).size());
}

}  // namespace

// =============================================================================================
// Random binary images against OpenCV and the reference

TEST(Blobs, RandomBinaryImagesMatchConnectedComponentsWithStats) {
  cv::RNG rng(kSeed);
  struct SizeRuns {
    cv::Size size;
    int runs;
  };
  const SizeRuns sizes[] = {{{1, 1}, 12}, {{37, 1}, 6},  {{1, 37}, 6},   {{2, 2}, 6},
                            {{3, 3}, 6},  {{64, 48}, 3}, {{257, 131}, 1}};
  for (const auto& [size, runs] : sizes) {
    for (double density : {0.05, 0.2, 0.4, 0.5, 0.6, 0.8}) {
      for (int r = 0; r < runs; ++r) {
        const cv::Mat src = random_binary(rng, size, density);
        SCOPED_TRACE("density " + std::to_string(density));
        for (k::Connectivity c : kBothConnectivities) expect_blobs_match_opencv(src, params(0, c));
      }
    }
  }
}

TEST(Blobs, RandomBinaryImagesMatchReference) {
  cv::RNG rng(kSeed);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(37, 1), cv::Size(1, 37), cv::Size(64, 48), cv::Size(257, 131)}) {
    for (double density : {0.05, 0.2, 0.4, 0.5, 0.6, 0.8}) {
      const cv::Mat src = random_binary(rng, size, density);
      SCOPED_TRACE("density " + std::to_string(density));
      for (k::Connectivity c : kBothConnectivities) expect_blobs_match_reference(src, params(0, c));
    }
  }
}

TEST(Blobs, GrayImagesWithThresholdsMatchOpenCvAndReference) {
  cv::RNG rng(kSeed);
  for (int t : {0, 1, 100, 128, 200, 254}) {
    const cv::Mat src = random_gray(rng, {rng.uniform(1, 120), rng.uniform(1, 90)});
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(src, params(t, c));
  }
}

// =============================================================================================
// Order and label image

TEST(Blobs, OrderIsFirstPixelInRasterOrder) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_binary(rng, {90, 70}, 0.3);
  for (k::Connectivity c : kBothConnectivities) {
    cv::Mat labels;
    const auto blobs = k::extract_blobs(src, params(0, c), cv::Mat(), &labels);
    // The first time each label appears in a raster scan, it must be the next one.
    int seen = 0;
    for (int y = 0; y < labels.rows; ++y) {
      for (int x = 0; x < labels.cols; ++x) {
        const int l = labels.at<int>(y, x);
        ASSERT_LE(l, seen + 1) << "at (" << x << ", " << y << "), " << conn_name(c);
        if (l == seen + 1) {
          ++seen;
          ASSERT_EQ(blobs[static_cast<size_t>(l - 1)].y0, y) << "blob " << l - 1 << " starts on row " << y;
        }
      }
    }
    EXPECT_EQ(seen, static_cast<int>(blobs.size()));
  }
}

TEST(Blobs, LabelImageIsReallocatedAndMarksEachBlob) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_binary(rng, {40, 30}, 0.4);
  cv::Mat labels(3, 3, CV_8UC1, cv::Scalar(9));  // wrong size and type: must be replaced
  const auto blobs = k::extract_blobs(src, params(0, k::Connectivity::eight), cv::Mat(), &labels);
  ASSERT_EQ(labels.type(), CV_32SC1);
  ASSERT_EQ(labels.size(), src.size());
  std::vector<std::int64_t> area(blobs.size() + 1, 0);
  for (int y = 0; y < src.rows; ++y) {
    for (int x = 0; x < src.cols; ++x) {
      const int l = labels.at<int>(y, x);
      ASSERT_EQ(l == 0, src.at<std::uint8_t>(y, x) == 0) << "at (" << x << ", " << y << ")";
      ASSERT_GE(l, 0);
      ASSERT_LE(l, static_cast<int>(blobs.size()));
      ++area[static_cast<size_t>(l)];
    }
  }
  for (size_t i = 0; i < blobs.size(); ++i) EXPECT_EQ(area[i + 1], blobs[i].area) << "blob " << i;

  // A label image that already has the right size and type is overwritten everywhere.
  cv::Mat reused(src.size(), CV_32SC1, cv::Scalar(-5));
  k::extract_blobs(src, params(0, k::Connectivity::eight), cv::Mat(), &reused);
  EXPECT_TRUE(same_labels(reused, labels));
}

// =============================================================================================
// Moments and weighted centroids

TEST(Blobs, SecondMomentsMatchCvMomentsOfEachComponent) {
  cv::RNG rng(kSeed);
  for (double density : {0.2, 0.5, 0.7}) {
    const cv::Mat src = random_binary(rng, {200, 150}, density);
    for (k::Connectivity c : kBothConnectivities) {
      cv::Mat labels;
      const auto blobs = k::extract_blobs(src, params(0, c), cv::Mat(), &labels);
      EXPECT_TRUE(moments_match_opencv(blobs, labels)) << "density " << density << ", " << conn_name(c);
    }
  }
}

TEST(Blobs, MomentsOfKnownShapes) {
  // A 5x3 rectangle at (10, 20): mu20 = 3 * (4+1+0+1+4) = 30, mu02 = 5 * (1+0+1) = 10, mu11 = 0.
  cv::Mat m(40, 30, CV_8UC1, cv::Scalar(0));
  m(cv::Rect(10, 20, 5, 3)).setTo(255);
  // A diagonal of 4 pixels (8-connected): mu20 = mu02 = mu11 = 2.25 + 0.25 + 0.25 + 2.25 = 5.
  for (int i = 0; i < 4; ++i) m.at<std::uint8_t>(2 + i, 2 + i) = 255;
  const auto blobs = k::extract_blobs(m, params(0, k::Connectivity::eight));
  ASSERT_EQ(blobs.size(), 2U);
  EXPECT_DOUBLE_EQ(blobs[0].mu20, 5);
  EXPECT_DOUBLE_EQ(blobs[0].mu11, 5);
  EXPECT_DOUBLE_EQ(blobs[0].mu02, 5);
  EXPECT_DOUBLE_EQ(blobs[0].cx, 3.5);
  EXPECT_EQ(blobs[1].area, 15);
  EXPECT_DOUBLE_EQ(blobs[1].cx, 12);
  EXPECT_DOUBLE_EQ(blobs[1].cy, 21);
  EXPECT_DOUBLE_EQ(blobs[1].mu20, 30);
  EXPECT_DOUBLE_EQ(blobs[1].mu02, 10);
  EXPECT_DOUBLE_EQ(blobs[1].mu11, 0);
}

TEST(Blobs, WeightedCentroidsMatchReferenceWithSrcAsWeights) {
  cv::RNG rng(kSeed);
  for (int t : {0, 60, 128, 220}) {
    const cv::Mat src = random_gray(rng, {rng.uniform(20, 140), rng.uniform(20, 100)});
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_reference(src, params(t, c));
  }
}

TEST(Blobs, WeightedCentroidsMatchReferenceWithSeparateWeights) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 6; ++i) {
    const cv::Size size(rng.uniform(20, 140), rng.uniform(20, 100));
    const cv::Mat src = random_binary(rng, size, 0.45);
    cv::Mat weights = random_gray(rng, size);
    if (i % 2) weights.setTo(0, random_binary(rng, size, 0.7));  // many zero weights
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_reference(src, params(0, c), weights);
  }
}

TEST(Blobs, WeightedCentroidLiesOnTheOnlyWeightedPixel) {
  cv::Mat src(10, 12, CV_8UC1, cv::Scalar(0));
  src(cv::Rect(1, 1, 5, 4)).setTo(255);
  src(cv::Rect(7, 6, 4, 3)).setTo(255);
  cv::Mat weights(src.size(), CV_8UC1, cv::Scalar(0));
  weights.at<std::uint8_t>(3, 4) = 17;
  weights.at<std::uint8_t>(8, 7) = 255;
  weights.at<std::uint8_t>(8, 10) = 255;
  weights.at<std::uint8_t>(0, 0) = 255;  // background weights do not count
  const auto blobs = k::extract_blobs(src, params(0, k::Connectivity::eight), weights);
  ASSERT_EQ(blobs.size(), 2U);
  EXPECT_DOUBLE_EQ(blobs[0].wcx, 4);
  EXPECT_DOUBLE_EQ(blobs[0].wcy, 3);
  EXPECT_DOUBLE_EQ(blobs[1].wcx, 8.5);
  EXPECT_DOUBLE_EQ(blobs[1].wcy, 8);
}

TEST(Blobs, AllZeroWeightsGiveTheUnweightedCentroid) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_binary(rng, {60, 40}, 0.4);
  const cv::Mat zeros(src.size(), CV_8UC1, cv::Scalar(0));
  for (k::Connectivity c : kBothConnectivities) {
    const auto blobs = k::extract_blobs(src, params(0, c), zeros);
    ASSERT_FALSE(blobs.empty());
    for (const auto& b : blobs) {
      EXPECT_EQ(b.wcx, b.cx) << describe(b);
      EXPECT_EQ(b.wcy, b.cy) << describe(b);
    }
  }
}

// =============================================================================================
// Thresholds -1 and 255

TEST(Blobs, ThresholdMinusOneGivesOneBlobCoveringTheFrame) {
  cv::RNG rng(kSeed);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(9, 1), cv::Size(1, 9), cv::Size(37, 23)}) {
    cv::Mat src = random_gray(rng, size);
    src.at<std::uint8_t>(0, 0) = 0;
    for (k::Connectivity c : kBothConnectivities) {
      SCOPED_TRACE(size_name(src) + ", " + conn_name(c));
      cv::Mat labels;
      const auto blobs = k::extract_blobs(src, params(-1, c), cv::Mat(), &labels);
      ASSERT_EQ(blobs.size(), 1U);
      const k::Blob& b = blobs[0];
      const double w = size.width;
      const double h = size.height;
      EXPECT_EQ(b.area, size.area());
      EXPECT_EQ(b.x0, 0);
      EXPECT_EQ(b.y0, 0);
      EXPECT_EQ(b.width, size.width);
      EXPECT_EQ(b.height, size.height);
      EXPECT_DOUBLE_EQ(b.cx, (w - 1) / 2);
      EXPECT_DOUBLE_EQ(b.cy, (h - 1) / 2);
      EXPECT_NEAR(b.mu20, h * w * (w * w - 1) / 12, 1e-9);
      EXPECT_NEAR(b.mu02, w * h * (h * h - 1) / 12, 1e-9);
      EXPECT_NEAR(b.mu11, 0, 1e-9);
      EXPECT_EQ(cv::countNonZero(labels != 1), 0);
      expect_blobs_match_both(src, params(-1, c));
    }
  }
}

TEST(Blobs, Threshold255GivesNoBlobs) {
  const cv::Mat white(13, 17, CV_8UC1, cv::Scalar(255));
  for (k::Connectivity c : kBothConnectivities) {
    cv::Mat labels;
    EXPECT_TRUE(k::extract_blobs(white, params(255, c), cv::Mat(), &labels).empty());
    ASSERT_EQ(labels.size(), white.size());
    EXPECT_EQ(cv::countNonZero(labels), 0);
    EXPECT_TRUE(k::extract_blobs(white, params(254, c)).size() == 1U);
  }
}

// =============================================================================================
// Shapes that stress run merging

TEST(BlobShapes, UShapesMergeTheirArms) {
  const cv::Mat m = u_shape();
  EXPECT_EQ(count_blobs(m, k::Connectivity::four), 2);
  EXPECT_EQ(count_blobs(m, k::Connectivity::eight), 2);
  for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
  // The inner U starts on row 1, above the outer one: it comes first.
  const auto blobs = k::extract_blobs(m, params(0, k::Connectivity::four));
  EXPECT_EQ(blobs[0].y0, 1);
  EXPECT_EQ(blobs[0].x0, 6);
  EXPECT_EQ(blobs[1].y0, 2);
}

TEST(BlobShapes, SpiralIsOneComponent) {
  for (int n : {5, 6, 21, 40}) {
    const cv::Mat m = spiral(n);
    SCOPED_TRACE("spiral " + std::to_string(n));
    EXPECT_EQ(count_blobs(m, k::Connectivity::four), 1);
    EXPECT_EQ(count_blobs(m, k::Connectivity::eight), 1);
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
    // Rotated and mirrored, so the runs join in other orders.
    for (int code : {cv::ROTATE_90_CLOCKWISE, cv::ROTATE_180, cv::ROTATE_90_COUNTERCLOCKWISE}) {
      cv::Mat r;
      cv::rotate(m, r, code);
      for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(r, params(0, c));
    }
  }
}

TEST(BlobShapes, DiagonalStaircasesJoinOnlyUnderEightConnectivity) {
  const int n = 17;
  const cv::Mat one = staircases(n, false);
  EXPECT_EQ(count_blobs(one, k::Connectivity::eight), 1);
  EXPECT_EQ(count_blobs(one, k::Connectivity::four), n);
  cv::Mat anti;
  cv::flip(one, anti, 1);
  EXPECT_EQ(count_blobs(anti, k::Connectivity::eight), 1);
  EXPECT_EQ(count_blobs(anti, k::Connectivity::four), n);
  const cv::Mat x = staircases(n, true);
  EXPECT_EQ(count_blobs(x, k::Connectivity::eight), 1);
  const cv::Mat wide = wide_staircase(n);
  EXPECT_EQ(count_blobs(wide, k::Connectivity::four), 1);
  EXPECT_EQ(count_blobs(wide, k::Connectivity::eight), 1);
  for (const cv::Mat* m : std::initializer_list<const cv::Mat*>{&one, &anti, &x, &wide}) {
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(*m, params(0, c));
  }
}

TEST(BlobShapes, CombTeethJoinAtTheBottom) {
  for (bool ragged : {false, true}) {
    const cv::Mat m = comb(12, 20, ragged);
    SCOPED_TRACE(ragged ? "ragged comb" : "comb");
    EXPECT_EQ(count_blobs(m, k::Connectivity::four), 1);
    EXPECT_EQ(count_blobs(m, k::Connectivity::eight), 1);
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
    // Several combs side by side and an upside-down one.
    cv::Mat wide;
    cv::hconcat(std::vector<cv::Mat>{m, cv::Mat::zeros(m.rows, 1, CV_8UC1), m, cv::Mat::zeros(m.rows, 1, CV_8UC1), m},
                wide);
    EXPECT_EQ(count_blobs(wide, k::Connectivity::four), 3);
    cv::Mat flipped;
    cv::flip(wide, flipped, 0);
    for (const cv::Mat* p : {&wide, &flipped}) {
      for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(*p, params(0, c));
    }
  }
}

TEST(BlobShapes, Checkerboards) {
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(2, 2), cv::Size(9, 1), cv::Size(1, 9), cv::Size(31, 17)}) {
    const cv::Mat m = checkerboard(size);
    SCOPED_TRACE(size_name(m));
    EXPECT_EQ(count_blobs(m, k::Connectivity::four), cv::countNonZero(m));
    if (size.width > 1 && size.height > 1) {
      EXPECT_EQ(count_blobs(m, k::Connectivity::eight), 1);
    }
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
  }
}

TEST(BlobShapes, ComponentsTouchingTheImageBorders) {
  for (const cv::Size size : {cv::Size(20, 15), cv::Size(9, 9)}) {
    for (const cv::Mat& m : {frame_touching(size), edge_blobs(size)}) {
      for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
    }
  }
  const cv::Mat ring = frame_touching({20, 15});
  const auto blobs = k::extract_blobs(ring, params(0, k::Connectivity::four));
  ASSERT_FALSE(blobs.empty());
  EXPECT_EQ(blobs[0].x0, 0);
  EXPECT_EQ(blobs[0].y0, 0);
  EXPECT_EQ(blobs[0].width, 20);
  EXPECT_EQ(blobs[0].height, 15);
}

// =============================================================================================
// Edge-case images and ROI views

TEST(BlobEdgeCases, TinyConstantAndBorderOnlyImages) {
  cv::RNG rng(kSeed);
  std::vector<cv::Mat> images{cv::Mat(1, 1, CV_8UC1, cv::Scalar(0)),  cv::Mat(1, 1, CV_8UC1, cv::Scalar(255)),
                              random_binary(rng, {29, 1}, 0.5),       random_binary(rng, {1, 29}, 0.5),
                              random_binary(rng, {2, 2}, 0.5),        random_binary(rng, {3, 3}, 0.5),
                              cv::Mat(9, 13, CV_8UC1, cv::Scalar(0)), cv::Mat(9, 13, CV_8UC1, cv::Scalar(255))};
  cv::Mat border_only = random_binary(rng, {13, 10}, 0.6);
  border_only(cv::Rect(1, 1, 11, 8)).setTo(0);
  images.push_back(border_only);
  for (const auto& m : images) {
    for (k::Connectivity c : kBothConnectivities) expect_blobs_match_both(m, params(0, c));
  }
  EXPECT_TRUE(k::extract_blobs(images[0], params(0, k::Connectivity::eight)).empty());
  EXPECT_EQ(k::extract_blobs(images[1], params(0, k::Connectivity::eight)).size(), 1U);
  EXPECT_EQ(k::extract_blobs(images[7], params(0, k::Connectivity::four)).size(), 1U);
}

TEST(BlobEdgeCases, RoiViewsGiveTheSameBlobsAsTheirCopies) {
  cv::RNG rng(kSeed);
  for (const cv::Rect rect : {cv::Rect(3, 4, 40, 25), cv::Rect(5, 0, 1, 30), cv::Rect(0, 7, 30, 1)}) {
    // Foreground around the view would join its blobs if the kernel read past the view.
    cv::Mat parent = random_binary(rng, {50, 40}, 0.5);
    const cv::Mat view = parent(rect);
    const cv::Mat copy = view.clone();
    cv::Mat wparent = random_gray(rng, {50, 40});
    const cv::Mat wview = wparent(rect);
    SCOPED_TRACE(size_name(view) + " view");
    for (k::Connectivity c : kBothConnectivities) {
      cv::Mat lv;
      cv::Mat lc;
      EXPECT_TRUE(identical_blobs(k::extract_blobs(view, params(0, c), wview, &lv),
                                  k::extract_blobs(copy, params(0, c), wview.clone(), &lc)));
      EXPECT_TRUE(same_labels(lv, lc));
      expect_blobs_match_both(view, params(0, c));
      expect_blobs_match_reference(view, params(0, c), wview);
    }
  }
}

// =============================================================================================
// Argument checks

TEST(Blobs, RejectsInvalidArguments) {
  const cv::Mat src(6, 7, CV_8UC1, cv::Scalar(1));
  EXPECT_THROW(k::extract_blobs(cv::Mat(6, 7, CV_16SC1), {}), k::KernelError);
  EXPECT_THROW(k::extract_blobs(cv::Mat(6, 7, CV_8UC3), {}), k::KernelError);
  EXPECT_THROW(k::extract_blobs(cv::Mat(), {}), k::KernelError);
  EXPECT_THROW(k::extract_blobs(src, params(-2, k::Connectivity::eight)), k::KernelError);
  EXPECT_THROW(k::extract_blobs(src, params(256, k::Connectivity::eight)), k::KernelError);
  EXPECT_THROW(k::extract_blobs(src, {}, cv::Mat(6, 8, CV_8UC1)), k::KernelError);
  EXPECT_THROW(k::extract_blobs(src, {}, cv::Mat(7, 7, CV_8UC1)), k::KernelError);
  EXPECT_THROW(k::extract_blobs(src, {}, cv::Mat(6, 7, CV_16UC1)), k::KernelError);
  EXPECT_NO_THROW(k::extract_blobs(src, params(-1, k::Connectivity::four)));
  EXPECT_NO_THROW(k::extract_blobs(src, params(255, k::Connectivity::four)));
}

// =============================================================================================
// BlobMoments: exact sums merge in any order

TEST(BlobMoments, MergingPartialSumsInAnyOrderGivesIdenticalBlobs) {
  cv::RNG rng(kSeed);
  const cv::Mat weights = random_gray(rng, {200, 100});
  struct RunSpec {
    int y, xs, xe;
  };
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<RunSpec> runs;
    const int n = rng.uniform(1, 30);
    for (int i = 0; i < n; ++i) {
      const int xs = rng.uniform(0, 199);
      runs.push_back({rng.uniform(0, 100), xs, rng.uniform(xs + 1, 201)});
    }
    k::BlobMoments all;
    k::BlobMoments first;
    k::BlobMoments second;
    const int cut = rng.uniform(0, n + 1);
    for (int i = 0; i < n; ++i) {
      const auto& r = runs[static_cast<size_t>(i)];
      all.add_run(r.y, r.xs, r.xe, weights.ptr<std::uint8_t>(r.y));
      (i < cut ? first : second).add_run(r.y, r.xs, r.xe, weights.ptr<std::uint8_t>(r.y));
    }
    k::BlobMoments ab = first;
    ab.merge(second);
    k::BlobMoments ba = second;
    ba.merge(first);
    const std::vector<k::Blob> expected{k::to_blob(all)};
    EXPECT_TRUE(identical_blobs({k::to_blob(ab)}, expected)) << "trial " << trial << ", cut " << cut;
    EXPECT_TRUE(identical_blobs({k::to_blob(ba)}, expected)) << "trial " << trial << ", cut " << cut;
    k::BlobMoments with_empty = all;
    with_empty.merge(k::BlobMoments{});
    EXPECT_TRUE(identical_blobs({k::to_blob(with_empty)}, expected));
  }
}
