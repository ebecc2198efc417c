// Point kernels: lut, threshold, otsu_threshold, alu, lut2, bgr_to_gray, limited_to_full_luma, convert_s16 and
// histogram.
// Each is held to OpenCV where OpenCV computes the same thing (cv::LUT, cv::threshold, cv::add, ...,
// cv::cvtColor, cv::calcHist) and to the scalar reference otherwise. Also checked: row-range (stripe)
// calls give the whole-frame result and write only their rows, argument errors throw KernelError,
// and edge-case images (1x1, one row, one column, 2x2, 3x3, constant, border-only, ROI views) work.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "kernels/alu.hpp"
#include "kernels/convert.hpp"
#include "kernels/gray.hpp"
#include "kernels/histogram.hpp"
#include "kernels/luma_range.hpp"
#include "kernels/lut.hpp"
#include "kernels/lut2.hpp"
#include "kernels/reference/reference.hpp"
#include "kernels/threshold.hpp"

namespace k = neopipe::kernels;
namespace ref = neopipe::kernels::reference;
using namespace neopipe::kernels::testing;  // NOLINT(google-build-using-namespace)

namespace {

constexpr std::uint64_t kSeed = 0x5eed'0001;
k::Lut random_lut(cv::RNG& rng) {
  k::Lut t{};
  for (auto& v : t) v = static_cast<std::uint8_t>(rng.uniform(0, 256));
  return t;
}

cv::Mat opencv_lut(const cv::Mat& src, const k::Lut& table) {
  const cv::Mat t(1, 256, CV_8UC1, const_cast<std::uint8_t*>(table.data()));
  cv::Mat dst;
  cv::LUT(src, t, dst);
  return dst;
}

cv::Mat run_lut(const cv::Mat& src, const k::Lut& table) {
  cv::Mat dst;
  k::lut(src, dst, table);
  return dst;
}

cv::Mat opencv_threshold(const cv::Mat& src, int t, int high) {
  cv::Mat dst;
  cv::threshold(src, dst, t, high, cv::THRESH_BINARY);
  return dst;
}

cv::Mat run_threshold(const cv::Mat& src, int t, std::uint8_t high) {
  cv::Mat dst;
  k::threshold(src, dst, t, high);
  return dst;
}

constexpr k::AluOp kAllOps[] = {k::AluOp::add, k::AluOp::sub,     k::AluOp::absdiff, k::AluOp::min,
                                k::AluOp::max, k::AluOp::bit_and, k::AluOp::bit_or,  k::AluOp::bit_xor};

cv::Mat opencv_alu(k::AluOp op, const cv::Mat& a, const cv::Mat& b) {
  cv::Mat dst;
  switch (op) {
    case k::AluOp::add:
      cv::add(a, b, dst);
      break;
    case k::AluOp::sub:
      cv::subtract(a, b, dst);
      break;
    case k::AluOp::absdiff:
      cv::absdiff(a, b, dst);
      break;
    case k::AluOp::min:
      cv::min(a, b, dst);
      break;
    case k::AluOp::max:
      cv::max(a, b, dst);
      break;
    case k::AluOp::bit_and:
      cv::bitwise_and(a, b, dst);
      break;
    case k::AluOp::bit_or:
      cv::bitwise_or(a, b, dst);
      break;
    case k::AluOp::bit_xor:
      cv::bitwise_xor(a, b, dst);
      break;
  }
  return dst;
}

cv::Mat run_alu(k::AluOp op, const cv::Mat& a, const cv::Mat& b) {
  cv::Mat dst;
  k::alu(op, a, b, dst);
  return dst;
}

/// Every pair: a(y, x) = y, b(y, x) = x on a 256x256 frame.
void all_pairs(cv::Mat& a, cv::Mat& b) {
  a.create(256, 256, CV_8UC1);
  b.create(256, 256, CV_8UC1);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      a.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(y);
      b.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(x);
    }
  }
}

struct NamedLut2 {
  std::string name;
  k::Lut2 table;
};

std::vector<NamedLut2> lut2_tables(cv::RNG& rng) {
  std::vector<NamedLut2> tables;
  tables.push_back({"identity on a", k::Lut2()});
  tables.push_back({"running average (3a + b) / 4", k::Lut2::from_function([](int a, int b) {
                      return static_cast<std::uint8_t>((3 * a + b + 2) / 4);
                    })});
  tables.push_back({"b", k::Lut2::from_function([](int, int b) { return static_cast<std::uint8_t>(b); })});
  tables.push_back(
      {"a > b", k::Lut2::from_function([](int a, int b) { return static_cast<std::uint8_t>(a > b ? 255 : 0); })});
  tables.push_back(
      {"(a * b) / 255", k::Lut2::from_function([](int a, int b) { return static_cast<std::uint8_t>(a * b / 255); })});
  k::Lut2 random;
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) random.at(a, b) = static_cast<std::uint8_t>(rng.uniform(0, 256));
  }
  tables.push_back({"random", random});
  return tables;
}

cv::Mat run_lut2(const cv::Mat& a, const cv::Mat& b, const k::Lut2& t) {
  cv::Mat dst;
  k::lut2(a, b, dst, t);
  return dst;
}

cv::Mat opencv_gray(const cv::Mat& bgr) {
  cv::Mat dst;
  cv::cvtColor(bgr, dst, cv::COLOR_BGR2GRAY);
  return dst;
}

cv::Mat run_gray(const cv::Mat& bgr) {
  cv::Mat dst;
  k::bgr_to_gray(bgr, dst);
  return dst;
}

cv::Mat run_convert(const cv::Mat& src, const k::ConvertS16& c) {
  cv::Mat dst;
  k::convert_s16(src, dst, c);
  return dst;
}

/// All 65,536 16-bit values once, in a 256x256 frame.
cv::Mat all_s16_values() {
  cv::Mat m(256, 256, CV_16SC1);
  for (int i = 0; i < 65536; ++i) m.at<std::int16_t>(i / 256, i % 256) = static_cast<std::int16_t>(i - 32768);
  return m;
}

::testing::AssertionResult same_histogram(const k::Histogram& actual, const k::Histogram& expected) {
  for (size_t i = 0; i < 256; ++i) {
    if (actual[i] != expected[i]) {
      return ::testing::AssertionFailure() << "bin " << i << ": actual " << actual[i] << ", expected " << expected[i];
    }
  }
  return ::testing::AssertionSuccess();
}

k::Histogram opencv_histogram(const cv::Mat& src) {
  cv::Mat h;
  const int channels[] = {0};
  const int bins[] = {256};
  const float range[] = {0, 256};
  const float* ranges[] = {range};
  cv::calcHist(&src, 1, channels, cv::Mat(), h, 1, bins, ranges, true, false);
  k::Histogram out{};
  for (int i = 0; i < 256; ++i) out[static_cast<size_t>(i)] = static_cast<std::uint64_t>(h.at<float>(i));
  return out;
}

int opencv_otsu(const cv::Mat& src) {
  cv::Mat dst;
  return static_cast<int>(cv::threshold(src, dst, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
}

cv::Mat gaussian_u8(cv::RNG& rng, cv::Size size, double mean, double sigma) {
  cv::Mat f(size, CV_32FC1);
  rng.fill(f, cv::RNG::NORMAL, mean, sigma);
  cv::Mat u;
  f.convertTo(u, CV_8UC1);  // rounds and saturates
  return u;
}

/// Images with the histograms Otsu meets in practice and some it should survive: uniform over a
/// random range, one or two Gaussian populations in random proportions, a few levels, constants.
cv::Mat otsu_image(cv::RNG& rng, int i) {
  const cv::Size size(rng.uniform(1, 90), rng.uniform(1, 90));
  switch (i % 6) {
    case 0: {
      cv::Mat m(size, CV_8UC1);
      const int lo = rng.uniform(0, 256);
      const int hi = rng.uniform(lo, 256) + 1;
      rng.fill(m, cv::RNG::UNIFORM, lo, hi);
      return m;
    }
    case 1:
    case 2: {
      const cv::Mat a = gaussian_u8(rng, size, rng.uniform(0.0, 128.0), rng.uniform(1.0, 30.0));
      const cv::Mat b = gaussian_u8(rng, size, rng.uniform(128.0, 256.0), rng.uniform(1.0, 30.0));
      cv::Mat pick(size, CV_32FC1);
      rng.fill(pick, cv::RNG::UNIFORM, 0.0, 1.0);
      cv::Mat out = a.clone();
      b.copyTo(out, pick < rng.uniform(0.05, 0.95));
      return out;
    }
    case 3:
      return gaussian_u8(rng, size, rng.uniform(0.0, 256.0), rng.uniform(0.5, 60.0));
    case 4: {
      cv::Mat idx(size, CV_8UC1);
      rng.fill(idx, cv::RNG::UNIFORM, 0, rng.uniform(2, 5));
      cv::Mat levels(1, 256, CV_8UC1, cv::Scalar(0));
      for (int l = 0; l < 5; ++l) levels.at<std::uint8_t>(l) = static_cast<std::uint8_t>(rng.uniform(0, 256));
      cv::Mat out;
      cv::LUT(idx, levels, out);
      return out;
    }
    default:
      return cv::Mat(size, CV_8UC1, cv::Scalar(rng.uniform(0, 256)));
  }
}

}  // namespace

// =============================================================================================
// lut

TEST(Lut, MatchesCvLutOnRandomTablesAndImages) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 20; ++i) {
    const k::Lut table = random_lut(rng);
    const cv::Mat src = random_image(rng, {rng.uniform(1, 120), rng.uniform(1, 90)}, CV_8UC1);
    SCOPED_TRACE(i);
    EXPECT_TRUE(same_image(run_lut(src, table), opencv_lut(src, table)));
    EXPECT_TRUE(same_image(run_lut(src, table), ref::lut(src, table)));
  }
}

TEST(Lut, IdentityAndInversionTables) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {64, 48}, CV_8UC1);
  EXPECT_TRUE(same_image(run_lut(src, k::identity_lut()), src));
  k::Lut invert{};
  for (int v = 0; v < 256; ++v) invert[static_cast<size_t>(v)] = static_cast<std::uint8_t>(255 - v);
  cv::Mat expected;
  cv::bitwise_not(src, expected);
  EXPECT_TRUE(same_image(run_lut(src, invert), expected));
}

TEST(Lut, EveryInputValueUsesItsOwnEntry) {
  cv::RNG rng(kSeed);
  const k::Lut table = random_lut(rng);
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int v = 0; v < 256; ++v) ramp.at<std::uint8_t>(v) = static_cast<std::uint8_t>(v);
  const cv::Mat out = run_lut(ramp, table);
  for (int v = 0; v < 256; ++v) EXPECT_EQ(out.at<std::uint8_t>(v), table[static_cast<size_t>(v)]) << "v " << v;
}

// =============================================================================================
// threshold

TEST(Threshold, MatchesCvThresholdBinaryForEveryT) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {37, 29}, CV_8UC1);
  for (int high : {255, 1, 128}) {
    for (int t = 0; t <= 255; ++t) {
      SCOPED_TRACE("T " + std::to_string(t) + ", high " + std::to_string(high));
      const cv::Mat out = run_threshold(src, t, static_cast<std::uint8_t>(high));
      ASSERT_TRUE(same_image(out, opencv_threshold(src, t, high)));
      ASSERT_TRUE(same_image(out, ref::threshold(src, t, static_cast<std::uint8_t>(high))));
    }
  }
}

TEST(Threshold, MinusOneMakesEveryPixelHigh) {
  cv::RNG rng(kSeed);
  cv::Mat src = random_image(rng, {41, 23}, CV_8UC1);
  src.at<std::uint8_t>(3, 4) = 0;  // zeros pass too
  for (int high : {255, 9}) {
    const cv::Mat out = run_threshold(src, -1, static_cast<std::uint8_t>(high));
    EXPECT_TRUE(same_image(out, ref::threshold(src, -1, static_cast<std::uint8_t>(high))));
    EXPECT_TRUE(same_image(out, cv::Mat(src.size(), CV_8UC1, cv::Scalar(high))));
    EXPECT_TRUE(same_image(out, opencv_threshold(src, -1, high)));
  }
}

TEST(Threshold, T255MakesEveryPixelZero) {
  const cv::Mat src(5, 7, CV_8UC1, cv::Scalar(255));
  EXPECT_TRUE(same_image(run_threshold(src, 255, 255), cv::Mat::zeros(src.size(), CV_8UC1)));
}

TEST(Threshold, RejectsTOutsideMinusOneTo255) {
  const cv::Mat src(4, 4, CV_8UC1, cv::Scalar(1));
  cv::Mat dst;
  EXPECT_THROW(k::threshold(src, dst, -2), k::KernelError);
  EXPECT_THROW(k::threshold(src, dst, 256), k::KernelError);
}

// =============================================================================================
// otsu_threshold

TEST(Otsu, MatchesCvThresholdOtsuOnRandomAndBimodalImages) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 1200; ++i) {
    const cv::Mat src = otsu_image(rng, i);
    const int expected = opencv_otsu(src);
    ASSERT_EQ(k::otsu_threshold(k::histogram(src)), expected)
        << "image " << i << " (kind " << i % 6 << ", " << src.cols << "x" << src.rows << ")";
  }
}

TEST(Otsu, SeparatesTwoWellSeparatedLevels) {
  // 40 pixels at 30 and 60 pixels at 200: any T in 30..199 separates them; Otsu picks the first.
  cv::Mat src(10, 10, CV_8UC1, cv::Scalar(200));
  src.rowRange(0, 4).setTo(30);
  const int t = k::otsu_threshold(k::histogram(src));
  EXPECT_EQ(t, opencv_otsu(src));
  EXPECT_GE(t, 30);
  EXPECT_LT(t, 200);
}

TEST(Otsu, ConstantImagesGiveZeroLikeOpenCv) {
  for (int v : {0, 1, 128, 255}) {
    const cv::Mat src(8, 9, CV_8UC1, cv::Scalar(v));
    EXPECT_EQ(k::otsu_threshold(k::histogram(src)), opencv_otsu(src)) << "value " << v;
  }
}

// =============================================================================================
// alu

TEST(Alu, EveryOpMatchesOpenCvOnEveryPairOfValues) {
  cv::Mat a;
  cv::Mat b;
  all_pairs(a, b);
  for (k::AluOp op : kAllOps) {
    SCOPED_TRACE(std::string(k::to_string(op)));
    EXPECT_TRUE(same_image(run_alu(op, a, b), opencv_alu(op, a, b)));
    EXPECT_TRUE(same_image(run_alu(op, b, a), opencv_alu(op, b, a)));
  }
}

TEST(Alu, EveryOpMatchesOpenCvAndReferenceOnRandomImages) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 8; ++i) {
    const cv::Size size(rng.uniform(1, 130), rng.uniform(1, 70));
    const cv::Mat a = random_image(rng, size, CV_8UC1);
    const cv::Mat b = random_image(rng, size, CV_8UC1);
    for (k::AluOp op : kAllOps) {
      SCOPED_TRACE(std::string(k::to_string(op)) + " image " + std::to_string(i));
      const cv::Mat out = run_alu(op, a, b);
      EXPECT_TRUE(same_image(out, opencv_alu(op, a, b)));
      EXPECT_TRUE(same_image(out, ref::alu(op, a, b)));
    }
  }
}

TEST(Alu, SaturatesAddAndSub) {
  const cv::Mat a(1, 3, CV_8UC1, cv::Scalar(200));
  cv::Mat b(1, 3, CV_8UC1);
  b.at<std::uint8_t>(0) = 100;
  b.at<std::uint8_t>(1) = 55;
  b.at<std::uint8_t>(2) = 255;
  const cv::Mat sum = run_alu(k::AluOp::add, a, b);
  EXPECT_EQ(sum.at<std::uint8_t>(0), 255);
  EXPECT_EQ(sum.at<std::uint8_t>(1), 255);
  EXPECT_EQ(sum.at<std::uint8_t>(2), 255);
  const cv::Mat diff = run_alu(k::AluOp::sub, b, a);
  EXPECT_EQ(diff.at<std::uint8_t>(0), 0);
  EXPECT_EQ(diff.at<std::uint8_t>(1), 0);
  EXPECT_EQ(diff.at<std::uint8_t>(2), 55);
}

TEST(Alu, OpNamesRoundTrip) {
  for (k::AluOp op : kAllOps) {
    const auto parsed = k::alu_op_from_string(k::to_string(op));
    ASSERT_TRUE(parsed.has_value()) << k::to_string(op);
    EXPECT_EQ(*parsed, op);
  }
  EXPECT_EQ(k::alu_op_from_string("and"), k::AluOp::bit_and);
  EXPECT_EQ(k::alu_op_from_string("xor"), k::AluOp::bit_xor);
  EXPECT_FALSE(k::alu_op_from_string("bit_and").has_value());
  EXPECT_FALSE(k::alu_op_from_string("").has_value());
  EXPECT_FALSE(k::alu_op_from_string("Add").has_value());
}

TEST(Alu, RejectsMismatchedOrMistypedInputs) {
  const cv::Mat a(6, 5, CV_8UC1, cv::Scalar(1));
  cv::Mat dst;
  EXPECT_THROW(k::alu(k::AluOp::add, a, cv::Mat(6, 6, CV_8UC1), dst), k::KernelError);
  EXPECT_THROW(k::alu(k::AluOp::add, a, cv::Mat(5, 5, CV_8UC1), dst), k::KernelError);
  EXPECT_THROW(k::alu(k::AluOp::add, a, cv::Mat(6, 5, CV_16SC1), dst), k::KernelError);
  EXPECT_THROW(k::alu(k::AluOp::add, cv::Mat(6, 5, CV_8UC3), a, dst), k::KernelError);
  EXPECT_THROW(k::alu(k::AluOp::add, a, cv::Mat(), dst), k::KernelError);
}

// =============================================================================================
// lut2

TEST(Lut2, MatchesReferenceOnEveryPairOfValues) {
  cv::RNG rng(kSeed);
  cv::Mat a;
  cv::Mat b;
  all_pairs(a, b);
  for (const auto& [name, table] : lut2_tables(rng)) {
    SCOPED_TRACE(name);
    const cv::Mat out = run_lut2(a, b, table);
    EXPECT_TRUE(same_image(out, ref::lut2(a, b, table)));
    for (int y = 0; y < 256; y += 51) {
      for (int x = 0; x < 256; x += 17) {
        ASSERT_EQ(out.at<std::uint8_t>(y, x), table(static_cast<std::uint8_t>(y), static_cast<std::uint8_t>(x)));
      }
    }
  }
}

TEST(Lut2, MatchesReferenceOnRandomImages) {
  cv::RNG rng(kSeed);
  const auto tables = lut2_tables(rng);
  for (int i = 0; i < 4; ++i) {
    const cv::Size size(rng.uniform(1, 100), rng.uniform(1, 60));
    const cv::Mat a = random_image(rng, size, CV_8UC1);
    const cv::Mat b = random_image(rng, size, CV_8UC1);
    for (const auto& [name, table] : tables) {
      SCOPED_TRACE(name);
      EXPECT_TRUE(same_image(run_lut2(a, b, table), ref::lut2(a, b, table)));
    }
  }
}

TEST(Lut2, DefaultTableIsIdentityOnA) {
  cv::RNG rng(kSeed);
  const cv::Mat a = random_image(rng, {33, 21}, CV_8UC1);
  const cv::Mat b = random_image(rng, {33, 21}, CV_8UC1);
  EXPECT_TRUE(same_image(run_lut2(a, b, k::Lut2()), a));
}

TEST(Lut2, RejectsMismatchedOrMistypedInputs) {
  const cv::Mat a(6, 5, CV_8UC1, cv::Scalar(1));
  cv::Mat dst;
  const k::Lut2 t;
  EXPECT_THROW(k::lut2(a, cv::Mat(5, 6, CV_8UC1), dst, t), k::KernelError);
  EXPECT_THROW(k::lut2(a, cv::Mat(6, 5, CV_16SC1), dst, t), k::KernelError);
  EXPECT_THROW(k::lut2(cv::Mat(6, 5, CV_8UC3), a, dst, t), k::KernelError);
}

// =============================================================================================
// bgr_to_gray

TEST(Gray, BitExactWithCvtColorOnEveryColour) {
  // 2^24 colours in a 4096x4096 frame: blue varies fastest, red slowest.
  cv::Mat bgr(4096, 4096, CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    auto* p = bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      const int i = y * 4096 + x;
      p[x] = cv::Vec3b(static_cast<std::uint8_t>(i & 255), static_cast<std::uint8_t>((i >> 8) & 255),
                       static_cast<std::uint8_t>(i >> 16));
    }
  }
  EXPECT_TRUE(same_image(run_gray(bgr), opencv_gray(bgr)));
}

TEST(Gray, MatchesCvtColorAndReferenceOnRandomImages) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 10; ++i) {
    const cv::Mat bgr = random_image(rng, {rng.uniform(1, 150), rng.uniform(1, 80)}, CV_8UC3);
    SCOPED_TRACE(i);
    const cv::Mat out = run_gray(bgr);
    EXPECT_TRUE(same_image(out, opencv_gray(bgr)));
    EXPECT_TRUE(same_image(out, ref::bgr_to_gray(bgr)));
  }
}

TEST(Gray, PrimariesAndWhite) {
  cv::Mat bgr(1, 5, CV_8UC3);
  bgr.at<cv::Vec3b>(0) = {0, 0, 0};
  bgr.at<cv::Vec3b>(1) = {255, 255, 255};
  bgr.at<cv::Vec3b>(2) = {255, 0, 0};
  bgr.at<cv::Vec3b>(3) = {0, 255, 0};
  bgr.at<cv::Vec3b>(4) = {0, 0, 255};
  const cv::Mat out = run_gray(bgr);
  EXPECT_EQ(out.at<std::uint8_t>(0), 0);
  EXPECT_EQ(out.at<std::uint8_t>(1), 255);
  EXPECT_EQ(out.at<std::uint8_t>(2), 29);   // 0.114 * 255 = 29.07
  EXPECT_EQ(out.at<std::uint8_t>(3), 150);  // 0.587 * 255 = 149.7
  EXPECT_EQ(out.at<std::uint8_t>(4), 76);   // 0.299 * 255 = 76.2
}

TEST(Gray, RejectsNonBgrInput) {
  cv::Mat dst;
  EXPECT_THROW(k::bgr_to_gray(cv::Mat(4, 4, CV_8UC1), dst), k::KernelError);
  EXPECT_THROW(k::bgr_to_gray(cv::Mat(4, 4, CV_8UC4), dst), k::KernelError);
  EXPECT_THROW(k::bgr_to_gray(cv::Mat(4, 4, CV_16UC3), dst), k::KernelError);
  EXPECT_THROW(k::bgr_to_gray(cv::Mat(), dst), k::KernelError);
}

// =============================================================================================
// limited_to_full_luma (the video reader's luma-plane gray)

TEST(LumaRange, EqualsTheFormulaForEveryInput) {
  for (int y = 0; y < 256; ++y) {
    // clamp(round((y - 16) * 255 / 219)); (y - 16) * 255 / 219 is never an exact half, so the
    // rounding direction of halves does not matter.
    const long want = std::clamp(std::lround((y - 16) * 255.0 / 219.0), 0L, 255L);
    EXPECT_EQ(k::limited_to_full_luma_exact(y), want) << "y = " << y;
    EXPECT_EQ(k::limited_to_full_luma(static_cast<std::uint8_t>(y)), want) << "y = " << y;
  }
  EXPECT_EQ(k::limited_to_full_luma(16), 0);
  EXPECT_EQ(k::limited_to_full_luma(235), 255);
  EXPECT_EQ(k::limited_to_full_luma(0), 0);
  EXPECT_EQ(k::limited_to_full_luma(255), 255);
}

TEST(LumaRange, RowFunctionEqualsTheFormulaAtEveryWidthAndOffset) {
  // Every value, at widths below, at and above a vector and with a ragged end, from unaligned
  // starts; and in place.
  std::vector<std::uint8_t> in(300 + 64);
  for (size_t i = 0; i < in.size(); ++i) in[i] = static_cast<std::uint8_t>((i * 7 + 3) & 255);
  for (const int width : {1, 7, 15, 16, 17, 31, 32, 33, 63, 64, 65, 100, 256, 300}) {
    for (const int offset : {0, 1, 3}) {
      const std::uint8_t* src = in.data() + offset;
      std::vector<std::uint8_t> out(static_cast<size_t>(width) + 1, 0xAB);
      k::limited_to_full_luma_row(src, out.data(), width);
      for (int x = 0; x < width; ++x) {
        ASSERT_EQ(out[static_cast<size_t>(x)], k::limited_to_full_luma_exact(src[x]))
            << "width " << width << ", offset " << offset << ", x " << x;
      }
      EXPECT_EQ(out.back(), 0xAB) << "wrote past the row, width " << width;
      std::vector<std::uint8_t> same(src, src + width);
      k::limited_to_full_luma_row(same.data(), same.data(), width);
      EXPECT_TRUE(std::equal(same.begin(), same.end(), out.begin())) << "in place, width " << width;
    }
  }
}

// =============================================================================================
// convert_s16

TEST(ConvertS16, MatchesReferenceOnEveryValueForEveryShift) {
  const cv::Mat src = all_s16_values();
  for (bool absolute : {true, false}) {
    for (int shift = 0; shift <= 15; ++shift) {
      SCOPED_TRACE(std::string(absolute ? "abs" : "signed") + " shift " + std::to_string(shift));
      const k::ConvertS16 c{absolute, shift};
      ASSERT_TRUE(same_image(run_convert(src, c), ref::convert_s16(src, c)));
    }
  }
}

TEST(ConvertS16, ExtremesAndHalves) {
  struct Probe {
    int v;
    bool absolute;
    int shift;
    int expected;
  };
  const Probe probes[] = {
      {-32768, true, 0, 255}, {32767, true, 0, 255},  {-32768, false, 0, 0}, {32767, false, 0, 255},
      {-32768, true, 7, 255}, {-32768, true, 8, 128}, {32767, true, 8, 128}, {-32768, true, 15, 1},
      {32767, false, 15, 1},  {16384, false, 15, 1},  {16383, false, 15, 0}, {-32768, false, 15, 0},
      {3, false, 1, 2},       {-3, true, 1, 2},       {-3, false, 1, 0},     {1, false, 1, 1},
      {-1, false, 1, 0},      {255, false, 0, 255},   {256, false, 0, 255},  {-1, true, 0, 1},
      {383, false, 1, 192},   {-200, true, 2, 50},    {0, true, 15, 0},      {510, false, 1, 255},
  };
  for (const auto& p : probes) {
    const cv::Mat src(1, 1, CV_16SC1, cv::Scalar(p.v));
    const k::ConvertS16 c{p.absolute, p.shift};
    const cv::Mat out = run_convert(src, c);
    EXPECT_EQ(out.at<std::uint8_t>(0), p.expected)
        << "v " << p.v << (p.absolute ? " abs" : " signed") << " shift " << p.shift;
    EXPECT_EQ(ref::convert_s16(src, c).at<std::uint8_t>(0), p.expected) << "reference, v " << p.v;
  }
}

TEST(ConvertS16, RejectsShiftOutside0To15AndWrongTypes) {
  const cv::Mat src(3, 3, CV_16SC1, cv::Scalar(5));
  cv::Mat dst;
  EXPECT_THROW(k::convert_s16(src, dst, {true, -1}), k::KernelError);
  EXPECT_THROW(k::convert_s16(src, dst, {true, 16}), k::KernelError);
  EXPECT_THROW(k::convert_s16(cv::Mat(3, 3, CV_8UC1), dst, {}), k::KernelError);
  EXPECT_THROW(k::convert_s16(cv::Mat(3, 3, CV_16UC1), dst, {}), k::KernelError);
  EXPECT_THROW(k::convert_s16(cv::Mat(3, 3, CV_16SC2), dst, {}), k::KernelError);
}

// =============================================================================================
// histogram

TEST(Histogram, MatchesCalcHistAndReference) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 12; ++i) {
    cv::Mat src = i % 3 == 0 ? gaussian_u8(rng, {rng.uniform(1, 300), rng.uniform(1, 200)}, 128, 40)
                             : random_image(rng, {rng.uniform(1, 300), rng.uniform(1, 200)}, CV_8UC1);
    SCOPED_TRACE(i);
    const k::Histogram h = k::histogram(src);
    EXPECT_TRUE(same_histogram(h, opencv_histogram(src)));
    EXPECT_TRUE(same_histogram(h, ref::histogram(src)));
    std::uint64_t total = 0;
    for (auto c : h) total += c;
    EXPECT_EQ(total, src.total());
  }
}

TEST(Histogram, StripesSumToTheWholeFrame) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {101, 67}, CV_8UC1);
  const k::Histogram whole = k::histogram(src);
  for (const auto& cuts : stripe_partitions(src.rows)) {
    k::Histogram sum{};
    for (size_t i = 0; i + 1 < cuts.size(); ++i) k::accumulate_histogram(src, sum, cv::Range(cuts[i], cuts[i + 1]));
    EXPECT_TRUE(same_histogram(sum, whole)) << "stripes cut every " << cuts[1] - cuts[0] << " rows";
  }
}

TEST(Histogram, AccumulateAddsToExistingCounts) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {23, 19}, CV_8UC1);
  k::Histogram h{};
  k::accumulate_histogram(src, h);
  k::accumulate_histogram(src, h);
  k::Histogram twice = ref::histogram(src);
  for (auto& c : twice) c *= 2;
  EXPECT_TRUE(same_histogram(h, twice));
}

TEST(Histogram, CountsOnlyTheRequestedRows) {
  cv::Mat src(6, 10, CV_8UC1, cv::Scalar(1));
  src.rowRange(2, 4).setTo(200);
  k::Histogram h{};
  k::accumulate_histogram(src, h, cv::Range(2, 4));
  EXPECT_EQ(h[200], 20U);
  EXPECT_EQ(h[1], 0U);
}

TEST(Histogram, RejectsWrongInput) {
  k::Histogram h{};
  EXPECT_THROW(k::accumulate_histogram(cv::Mat(3, 3, CV_8UC3), h), k::KernelError);
  EXPECT_THROW(k::accumulate_histogram(cv::Mat(3, 3, CV_16SC1), h), k::KernelError);
  EXPECT_THROW(k::histogram(cv::Mat()), k::KernelError);
}

// =============================================================================================
// Stripes (row ranges) and argument checks, for every point kernel

TEST(PointStripes, EveryKernelGivesTheWholeFrameResultWhenCutIntoStripes) {
  cv::RNG rng(kSeed);
  const cv::Size size(45, 31);
  const cv::Mat a = random_image(rng, size, CV_8UC1);
  const cv::Mat b = random_image(rng, size, CV_8UC1);
  const cv::Mat bgr = random_image(rng, size, CV_8UC3);
  const cv::Mat s16 = random_image(rng, size, CV_16SC1);
  const k::Lut table = random_lut(rng);
  const k::Lut2 table2 = lut2_tables(rng).back().table;
  {
    SCOPED_TRACE("lut");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::lut(a, d, table, r); });
  }
  {
    SCOPED_TRACE("threshold");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::threshold(a, d, 100, 200, r); });
  }
  {
    SCOPED_TRACE("threshold -1");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::threshold(a, d, -1, 255, r); });
  }
  for (k::AluOp op : kAllOps) {
    SCOPED_TRACE(std::string("alu ") + std::string(k::to_string(op)));
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::alu(op, a, b, d, r); });
  }
  {
    SCOPED_TRACE("lut2");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::lut2(a, b, d, table2, r); });
  }
  {
    SCOPED_TRACE("bgr_to_gray");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::bgr_to_gray(bgr, d, r); });
  }
  {
    SCOPED_TRACE("convert_s16");
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::convert_s16(s16, d, {true, 3}, r); });
  }
}

TEST(PointStripes, RowRangeNeedsAnOutputOfTheRightSizeAndType) {
  const cv::Size size(12, 9);
  const cv::Mat a(size, CV_8UC1, cv::Scalar(5));
  const cv::Mat bgr(size, CV_8UC3, cv::Scalar::all(5));
  const cv::Mat s16(size, CV_16SC1, cv::Scalar(5));
  const k::Lut table = k::identity_lut();
  const k::Lut2 table2;
  {
    SCOPED_TRACE("lut");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::lut(a, d, table, r); }, size, CV_8UC1);
  }
  {
    SCOPED_TRACE("threshold");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::threshold(a, d, 3, 255, r); }, size,
                                            CV_8UC1);
  }
  {
    SCOPED_TRACE("alu");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::alu(k::AluOp::add, a, a, d, r); }, size,
                                            CV_8UC1);
  }
  {
    SCOPED_TRACE("lut2");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::lut2(a, a, d, table2, r); }, size,
                                            CV_8UC1);
  }
  {
    SCOPED_TRACE("bgr_to_gray");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::bgr_to_gray(bgr, d, r); }, size, CV_8UC1);
  }
  {
    SCOPED_TRACE("convert_s16");
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::convert_s16(s16, d, {}, r); }, size,
                                            CV_8UC1);
  }
}

TEST(PointStripes, WrongInputTypeThrows) {
  cv::Mat dst;
  const cv::Mat s16(4, 4, CV_16SC1, cv::Scalar(1));
  const cv::Mat c3(4, 4, CV_8UC3, cv::Scalar::all(1));
  const cv::Mat empty;
  for (const cv::Mat* bad : {&s16, &c3, &empty}) {
    EXPECT_THROW(k::lut(*bad, dst, k::identity_lut()), k::KernelError);
    EXPECT_THROW(k::threshold(*bad, dst, 0), k::KernelError);
    EXPECT_THROW(k::alu(k::AluOp::max, *bad, *bad, dst), k::KernelError);
    EXPECT_THROW(k::lut2(*bad, *bad, dst, k::Lut2()), k::KernelError);
    EXPECT_THROW(k::histogram(*bad), k::KernelError);
  }
  const cv::Mat three_dims(std::vector<int>{2, 2, 2}, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(k::lut(three_dims, dst, k::identity_lut()), k::KernelError);
}

// =============================================================================================
// Edge-case images

TEST(PointEdgeCases, OneChannelKernelsOnEdgeCaseImages) {
  cv::RNG rng(kSeed);
  const k::Lut table = random_lut(rng);
  const k::Lut2 table2 = lut2_tables(rng)[1].table;
  for (const auto& [name, a] : edge_cases([&](cv::Size z) { return random_image(rng, z, CV_8UC1); }, CV_8UC1)) {
    SCOPED_TRACE(name);
    const cv::Mat b = random_image(rng, a.size(), CV_8UC1);
    EXPECT_TRUE(same_image(run_lut(a, table), opencv_lut(a, table)));
    for (int t : {-1, 0, 127, 254, 255}) {
      EXPECT_TRUE(same_image(run_threshold(a, t, 255), ref::threshold(a, t, 255))) << "T " << t;
      EXPECT_TRUE(same_image(run_threshold(a, t, 255), opencv_threshold(a, t, 255))) << "T " << t;
    }
    for (k::AluOp op : kAllOps) {
      EXPECT_TRUE(same_image(run_alu(op, a, b), opencv_alu(op, a, b))) << k::to_string(op);
      EXPECT_TRUE(same_image(run_alu(op, b, a), opencv_alu(op, b, a))) << k::to_string(op);
    }
    EXPECT_TRUE(same_image(run_lut2(a, b, table2), ref::lut2(a, b, table2)));
    EXPECT_TRUE(same_histogram(k::histogram(a), opencv_histogram(a)));
    EXPECT_EQ(k::otsu_threshold(k::histogram(a)), opencv_otsu(a));
  }
}

TEST(PointEdgeCases, GrayOnEdgeCaseImages) {
  cv::RNG rng(kSeed);
  for (const auto& [name, bgr] : edge_cases([&](cv::Size z) { return random_image(rng, z, CV_8UC3); }, CV_8UC3)) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(same_image(run_gray(bgr), opencv_gray(bgr)));
    EXPECT_TRUE(same_image(run_gray(bgr), ref::bgr_to_gray(bgr)));
  }
}

TEST(PointEdgeCases, ConvertOnEdgeCaseImages) {
  cv::RNG rng(kSeed);
  auto cases = edge_cases([&](cv::Size z) { return random_image(rng, z, CV_16SC1); }, CV_16SC1);
  cases.push_back({"all -32768", cv::Mat(5, 6, CV_16SC1, cv::Scalar(-32768))});
  for (const auto& [name, src] : cases) {
    SCOPED_TRACE(name);
    for (int shift : {0, 1, 8, 15}) {
      for (bool absolute : {true, false}) {
        const k::ConvertS16 c{absolute, shift};
        EXPECT_TRUE(same_image(run_convert(src, c), ref::convert_s16(src, c))) << "shift " << shift;
      }
    }
  }
}

TEST(PointEdgeCases, RoiViewsGiveTheSameResultAsTheirCopies) {
  cv::RNG rng(kSeed);
  const k::Lut table = random_lut(rng);
  cv::Mat parent = random_image(rng, {50, 40}, CV_8UC1);
  const cv::Mat a = parent(cv::Rect(5, 7, 31, 17));
  const cv::Mat b = random_image(rng, {60, 30}, CV_8UC1)(cv::Rect(20, 3, 31, 17));
  ASSERT_FALSE(a.isContinuous());
  ASSERT_FALSE(b.isContinuous());
  const cv::Mat ac = a.clone();
  const cv::Mat bc = b.clone();
  EXPECT_TRUE(same_image(run_lut(a, table), run_lut(ac, table)));
  EXPECT_TRUE(same_image(run_threshold(a, 90, 255), run_threshold(ac, 90, 255)));
  for (k::AluOp op : kAllOps) EXPECT_TRUE(same_image(run_alu(op, a, b), run_alu(op, ac, bc)));
  EXPECT_TRUE(same_image(run_lut2(a, b, k::Lut2()), ac));
  EXPECT_TRUE(same_histogram(k::histogram(a), k::histogram(ac)));

  // An ROI as the output: only the view is written.
  cv::Mat big(40, 50, CV_8UC1, cv::Scalar(kSentinel));
  cv::Mat view = big(cv::Rect(4, 6, a.cols, a.rows));
  k::lut(a, view, table);
  EXPECT_TRUE(same_image(view, opencv_lut(ac, table)));
  EXPECT_EQ(view.data, big.ptr(6) + 4) << "the whole-frame call reallocated a correctly sized view";
  cv::Mat outside = big.clone();
  outside(cv::Rect(4, 6, a.cols, a.rows)).setTo(kSentinel);
  EXPECT_EQ(cv::countNonZero(outside != kSentinel), 0);

  // Row ranges into a preallocated ROI view.
  cv::Mat big2(40, 50, CV_8UC1, cv::Scalar(kSentinel));
  cv::Mat view2 = big2(cv::Rect(2, 3, a.cols, a.rows));
  k::threshold(a, view2, 90, 255, cv::Range(0, 5));
  k::threshold(a, view2, 90, 255, cv::Range(5, a.rows));
  EXPECT_TRUE(same_image(view2, opencv_threshold(ac, 90, 255)));
}
