// Blobs of equal values (kernels/value_blobs.hpp), the blob kernel's s16 mode. Held to
// cv::connectedComponentsWithStats run on each value's mask (count, areas, boxes, centroids, label
// image) on random label images: overlapping rectangles and discs of a few values (touching regions
// of different values), of thousands of values, negative values, wide and one-row images; its
// second central moments to cv::moments; the scalar reference bit for bit.

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "kernel_test_support.hpp"
#include "kernels/reference/reference.hpp"
#include "kernels/value_blobs.hpp"

namespace k = neopipe::kernels;
namespace ref = neopipe::kernels::reference;
using neopipe::kernels::testing::describe;
using neopipe::kernels::testing::identical_blobs;
using neopipe::kernels::testing::same_geometry;

namespace {

constexpr std::uint64_t kSeed = 0x5eed'0020;
constexpr k::Connectivity kBothConnectivities[] = {k::Connectivity::four, k::Connectivity::eight};

// Rectangles and discs of random values painted over one another on a zero background: regions
// of different values touch and cut one another, and one value may have several components.
cv::Mat random_labels(cv::RNG& rng, cv::Size size, int shapes, int lo, int hi) {
  cv::Mat m(size, CV_16SC1, cv::Scalar(0));
  for (int i = 0; i < shapes; ++i) {
    int v = rng.uniform(lo, hi + 1);
    if (v == 0) v = 1;
    const cv::Point c(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const int r = rng.uniform(1, std::max(2, std::min(size.width, size.height) / 6));
    if (rng.uniform(0, 2) == 0) {
      cv::circle(m, c, r, cv::Scalar(v), cv::FILLED, cv::LINE_8);
    } else {
      const cv::Rect box(c.x - r, c.y - rng.uniform(0, r + 1), rng.uniform(1, 2 * r + 1), rng.uniform(1, r + 2));
      m(box & cv::Rect(0, 0, size.width, size.height)).setTo(v);
    }
  }
  return m;
}

// Noise of a few values: many tiny regions, diagonal neighbours of equal and different values.
cv::Mat random_pixels(cv::RNG& rng, cv::Size size, int values) {
  cv::Mat m(size, CV_16SC1);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) m.at<std::int16_t>(y, x) = static_cast<std::int16_t>(rng.uniform(0, values));
  }
  return m;
}

struct OpenCvValueComponents {
  std::vector<k::Blob> blobs;  ///< area, box, centroid and value; in first-pixel order
  cv::Mat labels;              ///< 0 background, i + 1 for blobs[i]
};

// cv::connectedComponentsWithStats on each value's mask, the components of every value numbered
// together by their first pixel in raster order.
OpenCvValueComponents opencv_value_components(const cv::Mat& src, k::Connectivity c) {
  std::map<int, std::pair<cv::Mat, cv::Mat>> per_value;  // value -> (labels, stats)
  std::map<int, cv::Mat> centroids;
  for (int y = 0; y < src.rows; ++y) {
    for (int x = 0; x < src.cols; ++x) {
      const int v = src.at<std::int16_t>(y, x);
      if (v == 0 || per_value.count(v) != 0) continue;
      cv::Mat labels;
      cv::Mat stats;
      cv::Mat cents;
      cv::connectedComponentsWithStats(src == v, labels, stats, cents, static_cast<int>(c), CV_32S);
      per_value[v] = {labels, stats};
      centroids[v] = cents;
    }
  }
  OpenCvValueComponents out;
  out.labels = cv::Mat(src.size(), CV_32SC1, cv::Scalar(0));
  std::map<std::pair<int, int>, int> rank;
  for (int y = 0; y < src.rows; ++y) {
    for (int x = 0; x < src.cols; ++x) {
      const int v = src.at<std::int16_t>(y, x);
      if (v == 0) continue;
      const auto& [labels, stats] = per_value[v];
      const int l = labels.at<int>(y, x);
      auto [it, fresh] = rank.try_emplace({v, l}, static_cast<int>(out.blobs.size()));
      if (fresh) {
        k::Blob b;
        b.area = stats.at<int>(l, cv::CC_STAT_AREA);
        b.x0 = stats.at<int>(l, cv::CC_STAT_LEFT);
        b.y0 = stats.at<int>(l, cv::CC_STAT_TOP);
        b.width = stats.at<int>(l, cv::CC_STAT_WIDTH);
        b.height = stats.at<int>(l, cv::CC_STAT_HEIGHT);
        b.cx = centroids[v].at<double>(l, 0);
        b.cy = centroids[v].at<double>(l, 1);
        b.value = v;
        out.blobs.push_back(b);
      }
      out.labels.at<int>(y, x) = it->second + 1;
    }
  }
  return out;
}

void expect_like_opencv(const cv::Mat& src, k::Connectivity c, const std::string& what) {
  SCOPED_TRACE(what + (c == k::Connectivity::four ? ", 4-connected" : ", 8-connected"));
  cv::Mat labels;
  const std::vector<k::Blob> got = k::extract_value_blobs(src, c, &labels);
  const OpenCvValueComponents want = opencv_value_components(src, c);
  ASSERT_EQ(got.size(), want.blobs.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_TRUE(same_geometry(got[i], want.blobs[i])) << "blob " << i;
    ASSERT_EQ(got[i].value, want.blobs[i].value) << "blob " << i << ": " << describe(got[i]);
    EXPECT_EQ(got[i].wcx, got[i].cx);
    EXPECT_EQ(got[i].wcy, got[i].cy);
  }
  EXPECT_EQ(cv::countNonZero(labels != want.labels), 0);
  // Second central moments of each component's mask.
  for (std::size_t i = 0; i < got.size(); ++i) {
    const cv::Moments m = cv::moments(labels == static_cast<int>(i) + 1, true);
    const double tol = 1e-6 * std::max(1.0, m.mu20 + m.mu02);
    EXPECT_NEAR(got[i].mu20, m.mu20, tol) << "blob " << i;
    EXPECT_NEAR(got[i].mu11, m.mu11, tol) << "blob " << i;
    EXPECT_NEAR(got[i].mu02, m.mu02, tol) << "blob " << i;
  }
  EXPECT_TRUE(identical_blobs(got, ref::value_blobs(src, c)));
}

TEST(ValueBlobs, MatchOpenCvOnOverlappingShapesOfAFewValues) {
  cv::RNG rng(kSeed);
  for (const cv::Size size : {cv::Size(64, 48), cv::Size(200, 120), cv::Size(37, 91)}) {
    for (int trial = 0; trial < 6; ++trial) {
      const cv::Mat src = random_labels(rng, size, 40, 1, 5);
      for (const auto c : kBothConnectivities)
        expect_like_opencv(src, c, "shapes of values 1..5, trial " + std::to_string(trial));
    }
  }
}

TEST(ValueBlobs, MatchOpenCvOnThousandsOfValuesNegativeOnesAndTheExtremes) {
  cv::RNG rng(kSeed + 1);
  const cv::Mat many = random_labels(rng, {300, 200}, 2000, -32768, 32767);
  for (const auto c : kBothConnectivities) expect_like_opencv(many, c, "2000 shapes of any value");
}

TEST(ValueBlobs, MatchOpenCvOnPixelNoise) {
  cv::RNG rng(kSeed + 2);
  for (const int values : {2, 3, 7}) {
    const cv::Mat src = random_pixels(rng, {80, 60}, values);
    for (const auto c : kBothConnectivities) expect_like_opencv(src, c, std::to_string(values) + " values of noise");
  }
}

TEST(ValueBlobs, MatchOpenCvOnWideAndOneRowImages) {
  cv::RNG rng(kSeed + 3);
  const cv::Mat ring = random_labels(rng, {3600, 40}, 300, 1, 400);
  for (const auto c : kBothConnectivities) expect_like_opencv(ring, c, "3600 x 40");
  const cv::Mat row = random_pixels(rng, {1001, 1}, 4);
  for (const auto c : kBothConnectivities) expect_like_opencv(row, c, "one row");
  const cv::Mat column = random_pixels(rng, {1, 333}, 4);
  for (const auto c : kBothConnectivities) expect_like_opencv(column, c, "one column");
}

TEST(ValueBlobs, TouchingRegionsOfDifferentValuesStayApart) {
  cv::Mat m(4, 6, CV_16SC1, cv::Scalar(0));
  m(cv::Rect(0, 0, 3, 4)).setTo(7);
  m(cv::Rect(3, 0, 3, 4)).setTo(8);
  const auto blobs = k::extract_value_blobs(m, k::Connectivity::eight);
  ASSERT_EQ(blobs.size(), 2U);
  EXPECT_EQ(blobs[0].value, 7);
  EXPECT_EQ(blobs[0].area, 12);
  EXPECT_EQ(blobs[1].value, 8);
  EXPECT_EQ(blobs[1].x0, 3);
  // Diagonal neighbours of one value join under 8-connectivity only; a different value between them
  // does not matter.
  cv::Mat d = (cv::Mat_<std::int16_t>(2, 2) << 5, 6, 6, 5);
  EXPECT_EQ(k::extract_value_blobs(d, k::Connectivity::eight).size(), 2U);
  EXPECT_EQ(k::extract_value_blobs(d, k::Connectivity::four).size(), 4U);
}

TEST(ValueBlobs, ReadsAViewOfALargerImage) {
  cv::RNG rng(kSeed + 4);
  const cv::Mat big = random_labels(rng, {120, 90}, 60, 1, 9);
  const cv::Mat view = big(cv::Rect(13, 7, 70, 50));
  EXPECT_TRUE(identical_blobs(k::extract_value_blobs(view, k::Connectivity::eight),
                              k::extract_value_blobs(view.clone(), k::Connectivity::eight)));
}

TEST(ValueBlobs, BlankImagesHaveNoBlobs) {
  EXPECT_TRUE(k::extract_value_blobs(cv::Mat(10, 10, CV_16SC1, cv::Scalar(0)), k::Connectivity::four).empty());
}

TEST(ValueBlobs, RefusesEmptyImagesOtherTypesAndConnectivities) {
  EXPECT_THROW(k::extract_value_blobs(cv::Mat(), k::Connectivity::eight), k::KernelError);
  EXPECT_THROW(k::extract_value_blobs(cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), k::Connectivity::eight), k::KernelError);
  EXPECT_THROW(k::extract_value_blobs(cv::Mat(4, 4, CV_16UC1, cv::Scalar(1)), k::Connectivity::eight), k::KernelError);
  EXPECT_THROW(k::extract_value_blobs(cv::Mat(4, 4, CV_16SC1, cv::Scalar(1)), static_cast<k::Connectivity>(6)),
               k::KernelError);
}

}  // namespace
