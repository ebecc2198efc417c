#pragma once
// What the kernel tests share: image comparison with a useful failure message, random and
// edge-case images, and the stripe checks every row-range kernel must pass.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

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

}  // namespace neopipe::kernels::testing
