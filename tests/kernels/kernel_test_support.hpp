#pragma once
// What the kernel tests share: image comparison with a useful failure message, random and
// edge-case images, the stripe checks every row-range kernel must pass, and for blob extraction
// blob comparison, OpenCV's view of the components and shapes that stress run merging.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "kernels/blobs.hpp"
#include "kernels/types.hpp"

namespace neopipe::kernels::testing {

/// Value a stripe test paints dst with, so rows a stripe call must not touch are recognisable.
inline constexpr int kSentinel = 77;

inline double value_at(const cv::Mat& one_channel, int y, int x) {
  switch (one_channel.depth()) {
    case CV_8U:
      return one_channel.at<std::uint8_t>(y, x);
    case CV_16S:
      return one_channel.at<std::int16_t>(y, x);
    case CV_32S:
      return one_channel.at<std::int32_t>(y, x);
    case CV_32F:
      return one_channel.at<float>(y, x);
    default:
      return one_channel.at<double>(y, x);
  }
}

/// Same size, type and values; on failure says how many values differ and shows the first.
inline ::testing::AssertionResult same_image(const cv::Mat& actual, const cv::Mat& expected) {
  if (actual.size() != expected.size() || actual.type() != expected.type()) {
    return ::testing::AssertionFailure() << "actual is " << actual.cols << "x" << actual.rows << " "
                                         << cv::typeToString(actual.type()) << ", expected " << expected.cols << "x"
                                         << expected.rows << " " << cv::typeToString(expected.type());
  }
  if (actual.empty()) return ::testing::AssertionSuccess();
  cv::Mat ne;
  cv::compare(actual, expected, ne, cv::CMP_NE);
  ne = ne.reshape(1);
  const int bad = cv::countNonZero(ne);
  if (bad == 0) return ::testing::AssertionSuccess();
  std::vector<cv::Point> where;
  cv::findNonZero(ne, where);
  const cv::Point p = where.front();
  const int cn = actual.channels();
  return ::testing::AssertionFailure() << bad << " of " << actual.total() * static_cast<size_t>(cn)
                                       << " values differ; first at (x " << p.x / cn << ", y " << p.y << ", channel "
                                       << p.x % cn << "): actual " << value_at(actual.reshape(1), p.y, p.x)
                                       << ", expected " << value_at(expected.reshape(1), p.y, p.x) << " (image "
                                       << actual.cols << "x" << actual.rows << ")";
}

/// Uniform random values over the whole range of the depth (0..255, or -32768..32767 for CV_16S).
inline cv::Mat random_image(cv::RNG& rng, cv::Size size, int type = CV_8UC1) {
  cv::Mat m(size, type);
  if (CV_MAT_DEPTH(type) == CV_16S) {
    rng.fill(m, cv::RNG::UNIFORM, -32768, 32768);
  } else {
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  }
  return m;
}

/// 0/255 with P(255) = density.
inline cv::Mat random_binary(cv::RNG& rng, cv::Size size, double density) {
  cv::Mat u(size, CV_32FC1);
  rng.fill(u, cv::RNG::UNIFORM, 0.0, 1.0);
  return u < density;
}

struct Case {
  std::string name;
  cv::Mat image;
};

using Fill = std::function<cv::Mat(cv::Size)>;

/// A non-continuous view of `size` inside a bigger image made by `fill`.
inline cv::Mat roi_view(const Fill& fill, cv::Size size) {
  cv::Mat parent = fill({size.width + 7, size.height + 5});
  return parent(cv::Rect(3, 2, size.width, size.height));
}

/// Shapes that stress the edges of a kernel's row loops: 1x1, single rows and columns, 2x2, 3x3,
/// constant images, content only on the border, ROI views. Random content comes from `fill`;
/// constant images have `type`.
inline std::vector<Case> edge_cases(const Fill& fill, int type = CV_8UC1) {
  const double top = CV_MAT_DEPTH(type) == CV_16S ? 32767 : 255;
  std::vector<Case> cases;
  cases.push_back({"1x1 random", fill({1, 1})});
  cases.push_back({"1x1 zero", cv::Mat(1, 1, type, cv::Scalar::all(0))});
  cases.push_back({"1x1 max", cv::Mat(1, 1, type, cv::Scalar::all(top))});
  cases.push_back({"one row 1x2", fill({2, 1})});
  cases.push_back({"one row 1x3", fill({3, 1})});
  cases.push_back({"one row 1x29", fill({29, 1})});
  cases.push_back({"one column 2x1", fill({1, 2})});
  cases.push_back({"one column 29x1", fill({1, 29})});
  cases.push_back({"2x2", fill({2, 2})});
  cases.push_back({"3x3", fill({3, 3})});
  cases.push_back({"2x7", fill({7, 2})});
  cases.push_back({"7x2", fill({2, 7})});
  cases.push_back({"all 0", cv::Mat(9, 13, type, cv::Scalar::all(0))});
  cases.push_back({"all max", cv::Mat(9, 13, type, cv::Scalar::all(top))});
  {
    cv::Mat b = fill({13, 10});
    b(cv::Rect(1, 1, b.cols - 2, b.rows - 2)).setTo(cv::Scalar::all(0));
    cases.push_back({"non-zero only on the border", b});
  }
  {
    cv::Mat b(10, 13, type, cv::Scalar::all(top));
    b(cv::Rect(1, 1, b.cols - 2, b.rows - 2)).setTo(cv::Scalar::all(0));
    cases.push_back({"max frame around zeros", b});
  }
  cases.push_back({"ROI 17x11", roi_view(fill, {17, 11})});
  cases.push_back({"ROI one row", roi_view(fill, {17, 1})});
  cases.push_back({"ROI one column", roi_view(fill, {1, 11})});
  cases.push_back({"ROI 2x2", roi_view(fill, {2, 2})});
  return cases;
}

/// Ways to cut `rows` rows into stripes (increasing cut points). Some reach beyond the image and
/// must be clamped; some stripes are empty.
inline std::vector<std::vector<int>> stripe_partitions(int rows) {
  std::vector<std::vector<int>> parts;
  for (int h : {1, 2, 5, std::max(1, rows / 3)}) {
    std::vector<int> cuts;
    for (int y = 0; y < rows; y += h) cuts.push_back(y);
    cuts.push_back(rows);
    parts.push_back(cuts);
  }
  parts.push_back({-3, 1, 1, rows / 2, rows / 2, rows + 9});
  return parts;
}

/// `run(dst, rows)` computes `rows` of dst (the whole frame for cv::Range::all()). Stripes into a
/// preallocated dst must give the whole-frame result and leave the other rows alone; a 3x3 kernel
/// reads the rows above and below its stripe from the input, not the output.
inline void expect_stripes_equal_whole_frame(const std::function<void(cv::Mat&, cv::Range)>& run) {
  cv::Mat whole;
  run(whole, cv::Range::all());
  ASSERT_FALSE(whole.empty());
  for (const auto& cuts : stripe_partitions(whole.rows)) {
    cv::Mat dst(whole.size(), whole.type(), cv::Scalar::all(kSentinel));
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
      const cv::Range r(cuts[i], cuts[i + 1]);
      const cv::Mat before = dst.clone();
      run(dst, r);
      for (int y = 0; y < dst.rows; ++y) {
        if (y >= r.start && y < r.end) continue;
        ASSERT_TRUE(same_image(dst.row(y), before.row(y)))
            << "stripe [" << r.start << ", " << r.end << ") wrote row " << y;
      }
    }
    EXPECT_TRUE(same_image(dst, whole)) << "stripes cut every " << cuts[1] - cuts[0] << " rows";
  }
}

/// A row-range call must find dst allocated with the input's size and `dst_type`; a whole-frame
/// call (re)allocates it instead.
inline void expect_row_range_needs_allocated_output(const std::function<void(cv::Mat&, cv::Range)>& run, cv::Size size,
                                                    int dst_type) {
  cv::Mat unallocated;
  EXPECT_THROW(run(unallocated, cv::Range(0, 1)), KernelError);
  cv::Mat taller(size.height + 1, size.width, dst_type);
  EXPECT_THROW(run(taller, cv::Range(0, 1)), KernelError);
  cv::Mat wider(size.height, size.width + 1, dst_type);
  EXPECT_THROW(run(wider, cv::Range(0, 1)), KernelError);
  const int wrong_type = dst_type == CV_8UC1 ? CV_32FC1 : CV_8UC1;
  cv::Mat mistyped(size, wrong_type);
  EXPECT_THROW(run(mistyped, cv::Range(0, 1)), KernelError);
  cv::Mat three_channels(size, CV_MAKETYPE(CV_MAT_DEPTH(dst_type), 3));
  EXPECT_THROW(run(three_channels, cv::Range(0, 1)), KernelError);
  cv::Mat wrong(size.height + 3, size.width + 2, wrong_type);
  EXPECT_NO_THROW(run(wrong, cv::Range::all()));
  EXPECT_EQ(wrong.size(), size);
  EXPECT_EQ(wrong.type(), dst_type);
}

// ---------------------------------------------------------------------------------------------
// Blobs (kernels/blobs.hpp)

/// Centroids agree with OpenCV's to this (absolute) tolerance.
inline constexpr double kCentroidTolerance = 1e-9;

inline std::string describe(const Blob& b) {
  std::ostringstream s;
  s.precision(17);
  s << "{area " << b.area << ", box (" << b.x0 << ", " << b.y0 << ") " << b.width << "x" << b.height << ", c (" << b.cx
    << ", " << b.cy << "), wc (" << b.wcx << ", " << b.wcy << "), mu20 " << b.mu20 << ", mu11 " << b.mu11 << ", mu02 "
    << b.mu02 << ", value " << b.value << "}";
  return s.str();
}

/// Area, bounding box and centroid (to kCentroidTolerance): what OpenCV's statistics give.
inline ::testing::AssertionResult same_geometry(const Blob& a, const Blob& e) {
  if (a.area == e.area && a.x0 == e.x0 && a.y0 == e.y0 && a.width == e.width && a.height == e.height &&
      std::abs(a.cx - e.cx) <= kCentroidTolerance && std::abs(a.cy - e.cy) <= kCentroidTolerance) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "actual " << describe(a) << "\nexpected " << describe(e);
}

/// Same count and order, every field equal, the floating-point ones bit for bit.
inline ::testing::AssertionResult identical_blobs(const std::vector<Blob>& a, const std::vector<Blob>& e) {
  if (a.size() != e.size()) return ::testing::AssertionFailure() << a.size() << " blobs, expected " << e.size();
  const auto same_bits = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
  };
  for (size_t i = 0; i < a.size(); ++i) {
    const auto& p = a[i];
    const auto& q = e[i];
    if (p.area != q.area || p.x0 != q.x0 || p.y0 != q.y0 || p.width != q.width || p.height != q.height ||
        !same_bits(p.cx, q.cx) || !same_bits(p.cy, q.cy) || !same_bits(p.wcx, q.wcx) || !same_bits(p.wcy, q.wcy) ||
        !same_bits(p.mu20, q.mu20) || !same_bits(p.mu11, q.mu11) || !same_bits(p.mu02, q.mu02) || p.value != q.value) {
      return ::testing::AssertionFailure() << "blob " << i << ": " << describe(p) << " vs " << describe(q);
    }
  }
  return ::testing::AssertionSuccess();
}

struct OpenCvComponents {
  std::vector<Blob> blobs;  ///< area, box and centroid only; in first-pixel order
  cv::Mat labels;           ///< 0 background, i + 1 for blobs[i]
};

/// cv::connectedComponentsWithStats on (src > threshold), renumbered by each component's first
/// pixel in raster order.
inline OpenCvComponents opencv_components(const cv::Mat& src, int threshold, Connectivity c) {
  const cv::Mat mask = src > threshold;
  cv::Mat cv_labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int n = cv::connectedComponentsWithStats(mask, cv_labels, stats, centroids, static_cast<int>(c), CV_32S);
  std::vector<int> rank(static_cast<size_t>(n), 0);
  int next = 0;
  OpenCvComponents out;
  out.labels.create(src.size(), CV_32SC1);
  for (int y = 0; y < src.rows; ++y) {
    for (int x = 0; x < src.cols; ++x) {
      const int l = cv_labels.at<int>(y, x);
      if (l != 0 && rank[static_cast<size_t>(l)] == 0) rank[static_cast<size_t>(l)] = ++next;
      out.labels.at<int>(y, x) = l == 0 ? 0 : rank[static_cast<size_t>(l)];
    }
  }
  out.blobs.resize(static_cast<size_t>(n - 1));
  for (int l = 1; l < n; ++l) {
    Blob& b = out.blobs[static_cast<size_t>(rank[static_cast<size_t>(l)] - 1)];
    b.area = stats.at<int>(l, cv::CC_STAT_AREA);
    b.x0 = stats.at<int>(l, cv::CC_STAT_LEFT);
    b.y0 = stats.at<int>(l, cv::CC_STAT_TOP);
    b.width = stats.at<int>(l, cv::CC_STAT_WIDTH);
    b.height = stats.at<int>(l, cv::CC_STAT_HEIGHT);
    b.cx = centroids.at<double>(l, 0);
    b.cy = centroids.at<double>(l, 1);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Shapes (0/255 images) that stress run merging

/// Two bars joined at the bottom: two runs per row until the last row merges them.
inline cv::Mat u_shape() {
  cv::Mat m(15, 20, CV_8UC1, cv::Scalar(0));
  m(cv::Rect(3, 2, 1, 11)).setTo(255);
  m(cv::Rect(12, 2, 1, 11)).setTo(255);
  m(cv::Rect(3, 12, 10, 1)).setTo(255);
  // A second, nested U whose arms start higher than the outer one's.
  m(cv::Rect(6, 1, 1, 9)).setTo(255);
  m(cv::Rect(9, 1, 1, 9)).setTo(255);
  m(cv::Rect(6, 9, 4, 1)).setTo(255);
  return m;
}

/// A square spiral with 1-px gaps: one component under both connectivities, with many runs per
/// row that join far away.
inline cv::Mat spiral(int n) {
  cv::Mat m(n, n, CV_8UC1, cv::Scalar(0));
  int x = 0;
  int y = 0;
  const int dx[] = {1, 0, -1, 0};
  const int dy[] = {0, 1, 0, -1};
  m.at<std::uint8_t>(y, x) = 255;
  int len = n - 1;
  for (int seg = 0; len > 0; ++seg) {
    for (int s = 0; s < len; ++s) {
      x += dx[seg % 4];
      y += dy[seg % 4];
      m.at<std::uint8_t>(y, x) = 255;
    }
    if (seg >= 2 && seg % 2 == 0) len -= 2;
  }
  return m;
}

/// Diagonal staircases, one pixel per row: joined only under 8-connectivity. The main diagonal
/// and the anti-diagonal cross, so under 8-connectivity they form one X.
inline cv::Mat staircases(int n, bool cross) {
  cv::Mat m(n, n + 4, CV_8UC1, cv::Scalar(0));
  for (int i = 0; i < n; ++i) {
    m.at<std::uint8_t>(i, i) = 255;
    if (cross) m.at<std::uint8_t>(i, n - 1 - i) = 255;
  }
  return m;
}

/// Steps two pixels wide: consecutive rows overlap by one pixel, so joined under both.
inline cv::Mat wide_staircase(int n) {
  cv::Mat m(n, n + 1, CV_8UC1, cv::Scalar(0));
  for (int i = 0; i < n; ++i) m(cv::Rect(i, i, 2, 1)).setTo(255);
  return m;
}

/// Teeth at even columns that join only at the bottom row. With `ragged`, the teeth start on
/// different rows, so their provisional labels are created out of left-to-right order.
inline cv::Mat comb(int teeth, int height, bool ragged) {
  cv::Mat m(height, 2 * teeth + 1, CV_8UC1, cv::Scalar(0));
  for (int t = 0; t < teeth; ++t) {
    const int top = ragged ? (t * 7) % (height - 1) : 0;
    m(cv::Rect(2 * t, top, 1, height - top)).setTo(255);
  }
  m.row(height - 1).setTo(255);
  return m;
}

/// Pixel checkerboard: under 8-connectivity one blob per colour, under 4 every pixel alone.
inline cv::Mat checkerboard(cv::Size size) {
  cv::Mat m(size, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < size.height; ++y) {
    for (int x = (y % 2); x < size.width; x += 2) m.at<std::uint8_t>(y, x) = 255;
  }
  return m;
}

/// A ring along the frame edges, plus blobs in the corners inside it and one touching it.
inline cv::Mat frame_touching(cv::Size size) {
  cv::Mat m(size, CV_8UC1, cv::Scalar(0));
  m.row(0).setTo(255);
  m.row(size.height - 1).setTo(255);
  m.col(0).setTo(255);
  m.col(size.width - 1).setTo(255);
  m(cv::Rect(2, 2, 3, 2)).setTo(255);                             // near the top-left corner
  m(cv::Rect(size.width - 4, size.height - 4, 2, 2)).setTo(255);  // near the bottom-right corner
  m(cv::Rect(size.width / 2, 1, 2, 3)).setTo(255);                // touches the top edge
  m.at<std::uint8_t>(size.height - 3, 2) = 255;                   // diagonal to nothing
  return m;
}

/// Components that touch only the image edges (no ring).
inline cv::Mat edge_blobs(cv::Size size) {
  cv::Mat m(size, CV_8UC1, cv::Scalar(0));
  m(cv::Rect(0, 0, 3, 2)).setTo(255);                             // top-left corner
  m(cv::Rect(size.width - 2, 0, 2, size.height)).setTo(255);      // whole right edge
  m(cv::Rect(0, size.height - 1, size.width / 2, 1)).setTo(255);  // part of the bottom row
  m(cv::Rect(0, 4, 1, 3)).setTo(255);                             // on the left edge
  return m;
}

}  // namespace neopipe::kernels::testing
