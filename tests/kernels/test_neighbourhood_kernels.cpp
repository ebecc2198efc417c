// 3x3 neighbourhood kernels: conv3x3 (with its presets) and bool3x3 (with its tables).
// conv3x3 with shift 0 is held to cv::filter2D (correlation, integer CV_32F kernel, anchor centre,
// delta 0) for BorderMode::replicate and constant borders; with shift > 0 to the scalar reference
// (halves round toward +infinity). bool3x3 erode/dilate tables are held to cv::erode/cv::dilate
// (3x3 MORPH_RECT), hit-or-miss tables to cv::morphologyEx(MORPH_HITMISS) on a 1-px replicated
// padding, random tables and constant borders to the reference. Also: stripes, argument errors,
// and edge-case images (1x1, one row, one column, 2x2, 3x3, constant, border-only, ROI views).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "kernels/bool3x3.hpp"
#include "kernels/conv3x3.hpp"
#include "kernels/reference/reference.hpp"

namespace k = neopipe::kernels;
namespace ref = neopipe::kernels::reference;
using namespace neopipe::kernels::testing;  // NOLINT(google-build-using-namespace)

namespace {

constexpr std::uint64_t kSeed = 0x5eed'0002;
using Weights = std::array<int, 9>;

/// Gray values where about half the pixels are 0: the Boolean kernels must treat any non-zero
/// value as set.
cv::Mat random_sparse_gray(cv::RNG& rng, cv::Size size) {
  cv::Mat g = random_image(rng, size);
  g.setTo(0, random_binary(rng, size, 0.5));
  return g;
}

// ---------------------------------------------------------------------------------------------
// conv3x3 helpers

k::Conv3x3 conv(const Weights& w, int shift = 0, k::Border border = {}) {
  return {w, shift, border};
}

k::Border replicate() {
  return {k::BorderMode::replicate, 0};
}
k::Border constant(int v) {
  return {k::BorderMode::constant, v};
}

std::string describe(const k::Conv3x3& c) {
  std::string s = "weights [";
  for (size_t i = 0; i < 9; ++i) {
    if (i > 0) s += ' ';
    s += std::to_string(c.weights[i]);
  }
  s += "] shift " + std::to_string(c.shift) +
       (c.border.mode == k::BorderMode::replicate ? " replicate" : " constant " + std::to_string(c.border.value));
  return s;
}

Weights random_weights(cv::RNG& rng, int max_abs) {
  Weights w{};
  for (auto& v : w) v = rng.uniform(-max_abs, max_abs + 1);
  return w;
}

cv::Mat run_conv(const cv::Mat& src, const k::Conv3x3& c, int dst_type) {
  cv::Mat dst;
  k::conv3x3(src, dst, c, dst_type);
  return dst;
}

/// cv::filter2D with the weights as an integer CV_32F kernel into CV_16S. Constant borders go
/// through an explicit 1-px padding, since filter2D's BORDER_CONSTANT is always 0. The input is
/// copied first so that an ROI's parent cannot leak in.
cv::Mat opencv_conv_s16(const cv::Mat& src, const Weights& w, const k::Border& border) {
  cv::Mat kernel(3, 3, CV_32FC1);
  for (int i = 0; i < 9; ++i) kernel.at<float>(i / 3, i % 3) = static_cast<float>(w[static_cast<size_t>(i)]);
  const cv::Mat s = src.clone();
  cv::Mat out;
  if (border.mode == k::BorderMode::replicate) {
    cv::filter2D(s, out, CV_16S, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
    return out;
  }
  cv::Mat padded;
  cv::copyMakeBorder(s, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(border.value));
  cv::filter2D(padded, out, CV_16S, kernel, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
  return out(cv::Rect(1, 1, src.cols, src.rows)).clone();
}

/// The same with the result saturated to 0..255.
cv::Mat opencv_conv_u8(const cv::Mat& src, const Weights& w, const k::Border& border) {
  cv::Mat u8;
  opencv_conv_s16(src, w, border).convertTo(u8, CV_8UC1);
  return u8;
}

/// conv3x3 with shift 0 against filter2D (both output types) and the reference.
void expect_conv_matches_opencv(const cv::Mat& src, const Weights& w, const k::Border& border) {
  const k::Conv3x3 c = conv(w, 0, border);
  SCOPED_TRACE(describe(c));
  const cv::Mat s16 = run_conv(src, c, CV_16SC1);
  EXPECT_TRUE(same_image(s16, opencv_conv_s16(src, w, border))) << "16-bit output";
  EXPECT_TRUE(same_image(s16, ref::conv3x3(src, c, CV_16SC1))) << "16-bit output vs reference";
  const cv::Mat u8 = run_conv(src, c, CV_8UC1);
  EXPECT_TRUE(same_image(u8, opencv_conv_u8(src, w, border))) << "8-bit output";
  EXPECT_TRUE(same_image(u8, ref::conv3x3(src, c, CV_8UC1))) << "8-bit output vs reference";
}

void expect_conv_matches_reference(const cv::Mat& src, const k::Conv3x3& c) {
  SCOPED_TRACE(describe(c));
  EXPECT_TRUE(same_image(run_conv(src, c, CV_16SC1), ref::conv3x3(src, c, CV_16SC1))) << "16-bit output";
  EXPECT_TRUE(same_image(run_conv(src, c, CV_8UC1), ref::conv3x3(src, c, CV_8UC1))) << "8-bit output";
}

std::vector<k::Border> all_borders() {
  return {replicate(), constant(0), constant(1), constant(128), constant(255)};
}

// ---------------------------------------------------------------------------------------------
// bool3x3 helpers

cv::Mat run_bool(const cv::Mat& src, const k::BoolTable& table, k::Border border = {}, std::uint8_t high = 255) {
  cv::Mat dst;
  k::bool3x3(src, dst, k::Bool3x3{table, high, border});
  return dst;
}

cv::Mat square3x3() {
  return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
}

/// OpenCV's morphology on the set pixels (non-zero) of src, as a 0/255 image.
cv::Mat opencv_erode(const cv::Mat& src) {
  cv::Mat out;
  cv::erode(src != 0, out, square3x3());
  return out;
}

cv::Mat opencv_dilate(const cv::Mat& src) {
  cv::Mat out;
  cv::dilate(src != 0, out, square3x3());
  return out;
}

/// '1' -> 1, '0' -> -1, 'x' -> 0, as cv::morphologyEx(MORPH_HITMISS) wants.
cv::Mat hitmiss_kernel(const std::string& pattern) {
  cv::Mat kernel(3, 3, CV_32SC1, cv::Scalar(0));
  int i = 0;
  for (char ch : pattern) {
    if (ch == ' ') continue;
    kernel.at<int>(i / 3, i % 3) = ch == '1' ? 1 : ch == '0' ? -1 : 0;
    ++i;
  }
  return kernel;
}

/// OpenCV's hit-or-miss treats the outside of the image as matching both '1' and '0'; padding the
/// input by one replicated pixel and cropping makes its border equal BorderMode::replicate.
cv::Mat opencv_hitmiss(const cv::Mat& src, const std::string& pattern) {
  cv::Mat padded;
  cv::copyMakeBorder(src != 0, padded, 1, 1, 1, 1, cv::BORDER_REPLICATE);
  cv::Mat out;
  cv::morphologyEx(padded, out, cv::MORPH_HITMISS, hitmiss_kernel(pattern));
  return out(cv::Rect(1, 1, src.cols, src.rows)).clone();
}

std::string random_pattern(cv::RNG& rng) {
  static const char kCells[] = {'1', '0', 'x'};
  for (;;) {
    std::string p;
    for (int i = 0; i < 9; ++i) p += kCells[rng.uniform(0, 3)];
    // An all-"x" kernel is empty to OpenCV, which then copies the input instead of matching.
    if (p != "xxxxxxxxx") return p;
  }
}

k::BoolTable random_table(cv::RNG& rng, double density) {
  std::bitset<512> bits;
  for (size_t i = 0; i < 512; ++i) bits[i] = rng.uniform(0.0, 1.0) < density;
  return k::BoolTable(bits);
}

/// Named patterns with a meaning, in reading order NW N NE / W C E / SW S SE.
const std::vector<std::string>& named_patterns() {
  static const std::vector<std::string> patterns{
      "000 010 000",  // isolated point
      "111 111 111",  // erosion
      "000 000 000",  // all clear ('0' only: OpenCV's first erosion is empty)
      "xxx x1x xxx",  // the centre alone
      "x1x 101 x1x",  // hole with a 4-connected ring
      "1x0 110 x0x",  // from the header
      "000 x1x 111",  // thinning step: top edge
      "x00 110 x1x",  // thinning step: corner
      "0xx xxx xxx",  // only the NW corner must be clear
      "xxx xxx xx1",  // only the SE corner must be set
      "010 111 010",  // plus
  };
  return patterns;
}

}  // namespace

// =============================================================================================
// conv3x3 against cv::filter2D (shift 0)

TEST(Conv3x3, Shift0MatchesFilter2DWithReplicateBorder) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 30; ++i) {
    const cv::Mat src = random_image(rng, {rng.uniform(1, 90), rng.uniform(1, 70)});
    // Up to +-12 the sums stay inside 16 bits; up to +-40 some saturate.
    expect_conv_matches_opencv(src, random_weights(rng, i % 3 == 0 ? 40 : 12), replicate());
  }
}

TEST(Conv3x3, Shift0MatchesFilter2DWithConstantBorders) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 30; ++i) {
    const cv::Mat src = random_image(rng, {rng.uniform(1, 90), rng.uniform(1, 70)});
    const int value = i % 5 == 0 ? 0 : i % 5 == 1 ? 255 : rng.uniform(0, 256);
    expect_conv_matches_opencv(src, random_weights(rng, 12), constant(value));
  }
}

TEST(Conv3x3, ZeroConstantBorderMatchesFilter2DBorderConstantDirectly) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {53, 37});
  const Weights w = random_weights(rng, 9);
  cv::Mat kernel(3, 3, CV_32FC1);
  for (int i = 0; i < 9; ++i) kernel.at<float>(i / 3, i % 3) = static_cast<float>(w[static_cast<size_t>(i)]);
  cv::Mat expected;
  cv::filter2D(src, expected, CV_16S, kernel, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
  EXPECT_TRUE(same_image(run_conv(src, conv(w, 0, constant(0)), CV_16SC1), expected));
}

TEST(Conv3x3, WeightsAreInReadingOrderAsCorrelation) {
  // A single weight at position i copies the neighbour at that position (no kernel flip).
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {20, 15});
  for (int i = 0; i < 9; ++i) {
    Weights w{};
    w[static_cast<size_t>(i)] = 1;
    const int dx = i % 3 - 1;
    const int dy = i / 3 - 1;
    const cv::Mat out = run_conv(src, conv(w), CV_8UC1);
    for (int y = 0; y < src.rows; ++y) {
      for (int x = 0; x < src.cols; ++x) {
        const int sx = std::clamp(x + dx, 0, src.cols - 1);
        const int sy = std::clamp(y + dy, 0, src.rows - 1);
        ASSERT_EQ(out.at<std::uint8_t>(y, x), src.at<std::uint8_t>(sy, sx))
            << "weight " << i << " at (" << x << ", " << y << ")";
      }
    }
    EXPECT_TRUE(same_image(out, opencv_conv_u8(src, w, replicate())));
  }
}

// =============================================================================================
// conv3x3 with a shift, against the reference

TEST(Conv3x3, ShiftedMatchesReferenceForEveryShiftAndBorder) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {47, 33});
  for (int shift = 0; shift <= 16; ++shift) {
    for (const auto& border : all_borders()) {
      for (int max_abs : {3, 300, 65535})
        expect_conv_matches_reference(src, conv(random_weights(rng, max_abs), shift, border));
    }
  }
}

// Rows wide enough for the SIMD interior (more than a vector of pixels plus the two border pixels,
// on every target), with weights on both sides of the 16-bit/32-bit choice: sums_fit_16_bits must
// send sums beyond -32768..32767 to the 32-bit path (tests/mutation/mutants.json, K08).
TEST(Conv3x3, WideRowsMatchReferenceOnBothSimdPaths) {
  cv::RNG rng(kSeed + 1);
  const cv::Mat src = random_image(rng, {203, 9});
  const cv::Mat white(5, 203, CV_8UC1, cv::Scalar(255));
  for (int shift : {0, 4, 9, 16}) {
    for (const auto& border : all_borders()) {
      for (int max_abs : {3, 14, 20, 28, 300, 65535})
        expect_conv_matches_reference(src, conv(random_weights(rng, max_abs), shift, border));
    }
    // 9 * 255 * 20 = 45900: over int16's range, under uint16's.
    expect_conv_matches_reference(white, conv({20, 20, 20, 20, 20, 20, 20, 20, 20}, shift));
    expect_conv_matches_reference(white, conv({-20, -20, -20, -20, -20, -20, -20, -20, -20}, shift));
  }
}

TEST(Conv3x3, RoundsHalvesTowardPlusInfinity) {
  // Centre weight +-1, shift 1: v / 2 with halves rounded up, for v = 0..255 and its negation.
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int v = 0; v < 256; ++v) ramp.at<std::uint8_t>(v) = static_cast<std::uint8_t>(v);
  const cv::Mat up = run_conv(ramp, conv({0, 0, 0, 0, 1, 0, 0, 0, 0}, 1), CV_16SC1);
  const cv::Mat down = run_conv(ramp, conv({0, 0, 0, 0, -1, 0, 0, 0, 0}, 1), CV_16SC1);
  for (int v = 0; v < 256; ++v) {
    const int floor_half = v / 2;  // v >= 0
    EXPECT_EQ(up.at<std::int16_t>(v), v % 2 ? floor_half + 1 : floor_half) << "+" << v << " / 2";
    EXPECT_EQ(down.at<std::int16_t>(v), -floor_half) << "-" << v << " / 2";  // -1.5 -> -1, -2 -> -2
  }
  // 3 / 4 = 0.75 -> 1, 2 / 4 -> 1 (half up), 1 / 4 -> 0, -2 / 4 -> 0, -6 / 4 = -1.5 -> -1.
  const cv::Mat px(1, 1, CV_8UC1, cv::Scalar(1));
  const auto one = [&](int w, int shift) {
    return run_conv(px, conv({0, 0, 0, 0, w, 0, 0, 0, 0}, shift), CV_16SC1).at<std::int16_t>(0);
  };
  EXPECT_EQ(one(3, 2), 1);
  EXPECT_EQ(one(2, 2), 1);
  EXPECT_EQ(one(1, 2), 0);
  EXPECT_EQ(one(-2, 2), 0);
  EXPECT_EQ(one(-6, 2), -1);
  EXPECT_EQ(one(-65535, 16), -1);  // -0.99998 -> -1
  EXPECT_EQ(one(32768, 16), 1);    // exactly 1/2 -> 1
  EXPECT_EQ(one(32767, 16), 0);
  EXPECT_EQ(one(-32768, 16), 0);  // exactly -1/2 -> 0
}

TEST(Conv3x3, SaturatesToTheOutputType) {
  const cv::Mat white(3, 3, CV_8UC1, cv::Scalar(255));
  const Weights big{65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535};
  const Weights neg{-65535, -65535, -65535, -65535, -65535, -65535, -65535, -65535, -65535};
  EXPECT_TRUE(same_image(run_conv(white, conv(big), CV_16SC1), cv::Mat(3, 3, CV_16SC1, cv::Scalar(32767))));
  EXPECT_TRUE(same_image(run_conv(white, conv(neg), CV_16SC1), cv::Mat(3, 3, CV_16SC1, cv::Scalar(-32768))));
  EXPECT_TRUE(same_image(run_conv(white, conv(big), CV_8UC1), cv::Mat(3, 3, CV_8UC1, cv::Scalar(255))));
  EXPECT_TRUE(same_image(run_conv(white, conv(neg), CV_8UC1), cv::Mat(3, 3, CV_8UC1, cv::Scalar(0))));
  // 9 * 65535 * 255 / 2^16 = 2294.9: still saturates 8-bit, not 16-bit.
  EXPECT_TRUE(same_image(run_conv(white, conv(big, 16), CV_16SC1), cv::Mat(3, 3, CV_16SC1, cv::Scalar(2295))));
  EXPECT_TRUE(same_image(run_conv(white, conv(big, 16), CV_8UC1), cv::Mat(3, 3, CV_8UC1, cv::Scalar(255))));
}

// =============================================================================================
// conv3x3 presets

TEST(Conv3x3, SobelPresetsMatchCvSobel) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 6; ++i) {
    const cv::Mat src = random_image(rng, {rng.uniform(1, 80), rng.uniform(1, 60)});
    cv::Mat gx;
    cv::Mat gy;
    cv::Sobel(src, gx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
    cv::Sobel(src, gy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REPLICATE);
    EXPECT_TRUE(same_image(run_conv(src, k::sobel_x3x3(), CV_16SC1), gx)) << "sobel x, image " << i;
    EXPECT_TRUE(same_image(run_conv(src, k::sobel_y3x3(), CV_16SC1), gy)) << "sobel y, image " << i;
  }
}

TEST(Conv3x3, SmoothPresetIsTheBinomialKernelRoundedHalfUp) {
  const k::Conv3x3 smooth = k::smooth3x3();
  EXPECT_EQ(smooth.weights, (Weights{1, 2, 1, 2, 4, 2, 1, 2, 1}));
  EXPECT_EQ(smooth.shift, 4);
  cv::RNG rng(kSeed);
  for (int i = 0; i < 6; ++i) {
    const cv::Mat src = random_image(rng, {rng.uniform(1, 80), rng.uniform(1, 60)});
    // filter2D gives the exact sum; (sum + 8) >> 4 rounds it half up.
    cv::Mat sum = opencv_conv_s16(src, smooth.weights, replicate());
    cv::Mat expected(src.size(), CV_8UC1);
    for (int y = 0; y < src.rows; ++y) {
      for (int x = 0; x < src.cols; ++x) {
        expected.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((sum.at<std::int16_t>(y, x) + 8) >> 4);
      }
    }
    EXPECT_TRUE(same_image(run_conv(src, smooth, CV_8UC1), expected)) << "image " << i;
    EXPECT_TRUE(same_image(run_conv(src, smooth, CV_8UC1), ref::conv3x3(src, smooth, CV_8UC1))) << "image " << i;
  }
}

TEST(Conv3x3, RejectsInvalidParameters) {
  const cv::Mat src(5, 5, CV_8UC1, cv::Scalar(1));
  cv::Mat dst;
  EXPECT_THROW(k::conv3x3(src, dst, conv({0, 0, 0, 0, 65536, 0, 0, 0, 0})), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, conv({-65536, 0, 0, 0, 1, 0, 0, 0, 0})), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, conv({0, 0, 0, 0, 1, 0, 0, 0, 0}, -1)), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, conv({0, 0, 0, 0, 1, 0, 0, 0, 0}, 17)), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, conv({0, 0, 0, 0, 1, 0, 0, 0, 0}, 0, constant(256))), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, conv({0, 0, 0, 0, 1, 0, 0, 0, 0}, 0, constant(-1))), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, k::Conv3x3{}, CV_32FC1), k::KernelError);
  EXPECT_THROW(k::conv3x3(src, dst, k::Conv3x3{}, CV_16UC1), k::KernelError);
  EXPECT_THROW(k::validate(conv({0, 0, 0, 0, 1, 0, 0, 0, 70000})), k::KernelError);
  EXPECT_NO_THROW(k::validate(conv({65535, -65535, 0, 0, 1, 0, 0, 0, 0}, 16, constant(255))));
  EXPECT_NO_THROW(k::validate(k::smooth3x3()));
}

TEST(Conv3x3, RejectsWrongInputTypes) {
  cv::Mat dst;
  EXPECT_THROW(k::conv3x3(cv::Mat(5, 5, CV_16SC1), dst, k::Conv3x3{}), k::KernelError);
  EXPECT_THROW(k::conv3x3(cv::Mat(5, 5, CV_8UC3), dst, k::Conv3x3{}), k::KernelError);
  EXPECT_THROW(k::conv3x3(cv::Mat(), dst, k::Conv3x3{}), k::KernelError);
}

// =============================================================================================
// bool3x3 against OpenCV morphology

TEST(Bool3x3, ErodeAndDilateTablesMatchCvErodeAndDilate) {
  cv::RNG rng(kSeed);
  for (double density : {0.1, 0.3, 0.5, 0.7, 0.9, 0.97}) {
    for (int i = 0; i < 4; ++i) {
      const cv::Mat src = random_binary(rng, {rng.uniform(1, 100), rng.uniform(1, 80)}, density);
      SCOPED_TRACE("density " + std::to_string(density) + ", " + std::to_string(src.cols) + "x" +
                   std::to_string(src.rows));
      EXPECT_TRUE(same_image(run_bool(src, k::erode_table()), opencv_erode(src))) << "erode";
      EXPECT_TRUE(same_image(run_bool(src, k::dilate_table()), opencv_dilate(src))) << "dilate";
    }
  }
}

TEST(Bool3x3, AnyNonZeroValueIsSetAndHighIsTheOutputValue) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_sparse_gray(rng, {71, 43});
  for (int high : {255, 1, 200}) {
    cv::Mat expected_erode = opencv_erode(src);
    cv::Mat expected_dilate = opencv_dilate(src);
    expected_erode.setTo(high, expected_erode);
    expected_dilate.setTo(high, expected_dilate);
    const auto h = static_cast<std::uint8_t>(high);
    EXPECT_TRUE(same_image(run_bool(src, k::erode_table(), {}, h), expected_erode)) << "high " << high;
    EXPECT_TRUE(same_image(run_bool(src, k::dilate_table(), {}, h), expected_dilate)) << "high " << high;
  }
}

TEST(Bool3x3, HitOrMissMatchesCvMorphologyExOnNamedPatterns) {
  cv::RNG rng(kSeed);
  for (const auto& pattern : named_patterns()) {
    for (double density : {0.2, 0.5, 0.8}) {
      const cv::Mat src = random_binary(rng, {rng.uniform(1, 70), rng.uniform(1, 50)}, density);
      SCOPED_TRACE("pattern \"" + pattern + "\", density " + std::to_string(density));
      EXPECT_TRUE(same_image(run_bool(src, k::hit_or_miss_table(pattern)), opencv_hitmiss(src, pattern)));
    }
  }
}

TEST(Bool3x3, HitOrMissMatchesCvMorphologyExOnRandomPatterns) {
  cv::RNG rng(kSeed);
  for (int i = 0; i < 60; ++i) {
    const std::string pattern = random_pattern(rng);
    const cv::Mat src = random_binary(rng, {rng.uniform(1, 60), rng.uniform(1, 40)}, rng.uniform(0.1, 0.9));
    SCOPED_TRACE("pattern \"" + pattern + "\"");
    EXPECT_TRUE(same_image(run_bool(src, k::hit_or_miss_table(pattern)), opencv_hitmiss(src, pattern)));
  }
}

// =============================================================================================
// bool3x3 against the reference

TEST(Bool3x3, RandomTablesMatchReferenceWithEveryBorder) {
  cv::RNG rng(kSeed);
  const std::vector<k::Border> borders{replicate(), constant(0), constant(255), constant(1), constant(-7)};
  for (int i = 0; i < 24; ++i) {
    const k::BoolTable table = random_table(rng, rng.uniform(0.05, 0.95));
    const cv::Mat src = i % 2 ? random_sparse_gray(rng, {rng.uniform(1, 70), rng.uniform(1, 50)})
                              : random_binary(rng, {rng.uniform(1, 70), rng.uniform(1, 50)}, 0.5);
    for (const auto& border : borders) {
      const k::Bool3x3 b{table, static_cast<std::uint8_t>(i % 3 ? 255 : 9), border};
      SCOPED_TRACE("table " + std::to_string(i) + ", border value " + std::to_string(border.value));
      cv::Mat out;
      k::bool3x3(src, out, b);
      EXPECT_TRUE(same_image(out, ref::bool3x3(src, b)));
    }
  }
}

TEST(Bool3x3, ConstantBorderActsAsSetOrClearOutsideTheImage) {
  // All-zero image: dilation sees the outside only where the border is set, so exactly the edge
  // pixels become set; erosion of an all-set image keeps the edge only if the outside is set.
  const cv::Mat zeros(6, 8, CV_8UC1, cv::Scalar(0));
  const cv::Mat ones(6, 8, CV_8UC1, cv::Scalar(255));
  cv::Mat edge(6, 8, CV_8UC1, cv::Scalar(255));
  edge(cv::Rect(1, 1, 6, 4)).setTo(0);
  cv::Mat interior(6, 8, CV_8UC1, cv::Scalar(0));
  interior(cv::Rect(1, 1, 6, 4)).setTo(255);
  EXPECT_TRUE(same_image(run_bool(zeros, k::dilate_table(), constant(1)), edge));
  EXPECT_TRUE(same_image(run_bool(zeros, k::dilate_table(), constant(0)), zeros));
  EXPECT_TRUE(same_image(run_bool(ones, k::erode_table(), constant(0)), interior));
  EXPECT_TRUE(same_image(run_bool(ones, k::erode_table(), constant(255)), ones));
  EXPECT_TRUE(same_image(run_bool(ones, k::erode_table(), replicate()), ones));
}

TEST(Bool3x3, EveryIndexBitIsTheDocumentedNeighbour) {
  // A table that is set only for index 1 << i fires where exactly neighbour i is set: a single
  // set pixel at P fires at the pixel that sees P at position i.
  for (int i = 0; i < 9; ++i) {
    std::bitset<512> bits;
    bits[static_cast<size_t>(1) << i] = true;
    cv::Mat src(7, 7, CV_8UC1, cv::Scalar(0));
    src.at<std::uint8_t>(3, 3) = 255;
    const cv::Mat out = run_bool(src, k::BoolTable(bits), constant(0));
    const int dx = i % 3 - 1;
    const int dy = i / 3 - 1;
    cv::Mat expected(7, 7, CV_8UC1, cv::Scalar(0));
    expected.at<std::uint8_t>(3 - dy, 3 - dx) = 255;
    EXPECT_TRUE(same_image(out, expected)) << "bit " << i;
  }
}

// =============================================================================================
// bool3x3 tables

TEST(Bool3x3, ErodeAndDilateTablesAreAsDocumented) {
  const auto erode = k::erode_table();
  const auto dilate = k::dilate_table();
  for (unsigned i = 0; i < 512; ++i) {
    EXPECT_EQ(erode[i], i == 511) << i;
    EXPECT_EQ(dilate[i], i != 0) << i;
  }
  const auto f = k::BoolTable::from_function([](unsigned i) { return (i & 16U) != 0; });
  EXPECT_EQ(f.bits().count(), 256U);
  EXPECT_EQ(f.bits(), k::hit_or_miss_table("xxxx1xxxx").bits());
}

TEST(Bool3x3, HitOrMissTableFollowsThePattern) {
  const auto t = k::hit_or_miss_table("1x0 110 x0x");
  // '1' at bits 0, 3, 4; '0' at bits 2, 5, 7; 'x' at 1, 6, 8.
  for (unsigned i = 0; i < 512; ++i) {
    const bool expected = (i & 0b000011001U) == 0b000011001U && (i & 0b010100100U) == 0;
    ASSERT_EQ(t[i], expected) << i;
  }
  EXPECT_EQ(k::hit_or_miss_table("xxxxxxxxx").bits().count(), 512U);
  EXPECT_EQ(k::hit_or_miss_table("111111111").bits(), k::erode_table().bits());
  EXPECT_EQ(k::hit_or_miss_table("000000000").bits().count(), 1U);
}

TEST(Bool3x3, HitOrMissPatternSyntax) {
  const auto bits = k::hit_or_miss_table("1x0110x0x").bits();
  EXPECT_EQ(k::hit_or_miss_table("1x0 110 x0x").bits(), bits);
  EXPECT_EQ(k::hit_or_miss_table("1.0 110 .0.").bits(), bits);
  EXPECT_EQ(k::hit_or_miss_table("1X0\n110\nX0X").bits(), bits);
  EXPECT_EQ(k::hit_or_miss_table(" 1x0  110  x0x ").bits(), bits);
}

TEST(Bool3x3, InvalidHitOrMissPatternsThrow) {
  EXPECT_THROW(k::hit_or_miss_table(""), k::KernelError);
  EXPECT_THROW(k::hit_or_miss_table("11110000"), k::KernelError);     // eight cells
  EXPECT_THROW(k::hit_or_miss_table("1111000011"), k::KernelError);   // ten cells
  EXPECT_THROW(k::hit_or_miss_table("111 101 112"), k::KernelError);  // bad character
  EXPECT_THROW(k::hit_or_miss_table("111 1-1 111"), k::KernelError);
  EXPECT_THROW(k::hit_or_miss_table("abc def ghi"), k::KernelError);
}

TEST(Bool3x3, RejectsWrongInputTypes) {
  cv::Mat dst;
  const k::Bool3x3 b{k::erode_table(), 255, {}};
  EXPECT_THROW(k::bool3x3(cv::Mat(5, 5, CV_16SC1), dst, b), k::KernelError);
  EXPECT_THROW(k::bool3x3(cv::Mat(5, 5, CV_8UC3), dst, b), k::KernelError);
  EXPECT_THROW(k::bool3x3(cv::Mat(), dst, b), k::KernelError);
}

// =============================================================================================
// Stripes

TEST(NeighbourhoodStripes, ConvGivesTheWholeFrameResultWhenCutIntoStripes) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {41, 29});
  for (const auto& border : {replicate(), constant(200)}) {
    for (int dst_type : {CV_8UC1, CV_16SC1}) {
      const k::Conv3x3 c = conv(random_weights(rng, 20), 2, border);
      SCOPED_TRACE(describe(c) + (dst_type == CV_8UC1 ? " 8-bit" : " 16-bit"));
      expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::conv3x3(src, d, c, dst_type, r); });
    }
  }
}

TEST(NeighbourhoodStripes, ConvRowRangeTakesTheOutputTypeFromDst) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_image(rng, {19, 13});
  const k::Conv3x3 c = k::sobel_x3x3();
  cv::Mat dst(src.size(), CV_16SC1, cv::Scalar(0));
  k::conv3x3(src, dst, c, CV_8UC1, cv::Range(0, src.rows));  // dst_type is ignored for stripes
  EXPECT_EQ(dst.type(), CV_16SC1);
  EXPECT_TRUE(same_image(dst, run_conv(src, c, CV_16SC1)));
}

TEST(NeighbourhoodStripes, BoolGivesTheWholeFrameResultWhenCutIntoStripes) {
  cv::RNG rng(kSeed);
  const cv::Mat src = random_sparse_gray(rng, {43, 31});
  for (const auto& border : {replicate(), constant(0), constant(255)}) {
    for (const auto& table : {k::erode_table(), k::dilate_table(), random_table(rng, 0.5)}) {
      const k::Bool3x3 b{table, 255, border};
      SCOPED_TRACE("border value " + std::to_string(border.value));
      expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::bool3x3(src, d, b, r); });
    }
  }
}

TEST(NeighbourhoodStripes, RowRangeNeedsAnOutputOfTheRightSizeAndType) {
  const cv::Size size(12, 9);
  const cv::Mat src(size, CV_8UC1, cv::Scalar(5));
  {
    SCOPED_TRACE("conv3x3");
    expect_row_range_needs_allocated_output(
        [&](cv::Mat& d, cv::Range r) { k::conv3x3(src, d, k::smooth3x3(), CV_8UC1, r); }, size, CV_8UC1);
  }
  {
    SCOPED_TRACE("bool3x3");
    const k::Bool3x3 b{k::erode_table(), 255, {}};
    expect_row_range_needs_allocated_output([&](cv::Mat& d, cv::Range r) { k::bool3x3(src, d, b, r); }, size, CV_8UC1);
  }
}

// =============================================================================================
// Edge-case images

TEST(NeighbourhoodEdgeCases, ConvOnEdgeCaseImages) {
  cv::RNG rng(kSeed);
  const std::vector<Weights> weights{k::sobel_x3x3().weights,
                                     k::sobel_y3x3().weights,
                                     k::smooth3x3().weights,
                                     random_weights(rng, 12),
                                     {1, 1, 1, 1, 1, 1, 1, 1, 1}};
  for (const auto& [name, src] : edge_cases([&](cv::Size s) { return random_image(rng, s); })) {
    SCOPED_TRACE(name);
    for (const auto& w : weights) {
      for (const auto& border : {replicate(), constant(0), constant(255), constant(33)}) {
        expect_conv_matches_opencv(src, w, border);
        expect_conv_matches_reference(src, conv(w, 3, border));
      }
    }
  }
}

TEST(NeighbourhoodEdgeCases, BoolOnEdgeCaseImages) {
  cv::RNG rng(kSeed);
  const auto fill = [&](cv::Size s) { return random_binary(rng, s, 0.6); };
  const k::BoolTable table = random_table(rng, 0.5);
  for (const auto& [name, src] : edge_cases(fill)) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(same_image(run_bool(src, k::erode_table()), opencv_erode(src))) << "erode";
    EXPECT_TRUE(same_image(run_bool(src, k::dilate_table()), opencv_dilate(src))) << "dilate";
    for (const auto& pattern : named_patterns()) {
      EXPECT_TRUE(same_image(run_bool(src, k::hit_or_miss_table(pattern)), opencv_hitmiss(src, pattern)))
          << "pattern " << pattern;
    }
    for (const auto& border : {replicate(), constant(0), constant(255)}) {
      const k::Bool3x3 b{table, 255, border};
      cv::Mat out;
      k::bool3x3(src, out, b);
      EXPECT_TRUE(same_image(out, ref::bool3x3(src, b))) << "random table, border value " << border.value;
    }
  }
}

TEST(NeighbourhoodEdgeCases, RoiViewsDoNotReadOutsideTheView) {
  // The parent differs from the view's edge pixels, so reading past the view would show.
  cv::RNG rng(kSeed);
  for (const cv::Rect rect :
       {cv::Rect(3, 4, 20, 13), cv::Rect(5, 6, 1, 9), cv::Rect(2, 7, 15, 1), cv::Rect(8, 8, 2, 2)}) {
    const cv::Mat parent = random_image(rng, {30, 25});
    const cv::Mat view = parent(rect);
    const cv::Mat copy = view.clone();
    SCOPED_TRACE(std::to_string(rect.width) + "x" + std::to_string(rect.height) + " view");
    for (const auto& border : {replicate(), constant(9)}) {
      const k::Conv3x3 c = conv({1, 2, 3, 4, 5, 6, 7, 8, 9}, 2, border);
      EXPECT_TRUE(same_image(run_conv(view, c, CV_16SC1), run_conv(copy, c, CV_16SC1)));
      EXPECT_TRUE(same_image(run_conv(view, c, CV_16SC1), ref::conv3x3(copy, c, CV_16SC1)));
      const cv::Mat bview = view > 128;
      const cv::Mat bparent = parent > 128;
      const cv::Mat bview_in_parent = bparent(rect);
      const k::Bool3x3 b{k::dilate_table(), 255, border};
      cv::Mat out;
      k::bool3x3(bview_in_parent, out, b);
      EXPECT_TRUE(same_image(out, ref::bool3x3(bview, b)));
    }
  }
}

TEST(NeighbourhoodEdgeCases, RowRangesOnTinyImages) {
  cv::RNG rng(kSeed);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(5, 1), cv::Size(1, 5), cv::Size(2, 2), cv::Size(3, 3)}) {
    const cv::Mat src = random_image(rng, size);
    SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height));
    expect_stripes_equal_whole_frame(
        [&](cv::Mat& d, cv::Range r) { k::conv3x3(src, d, k::sobel_x3x3(), CV_16SC1, r); });
    const k::Bool3x3 b{k::dilate_table(), 255, constant(0)};
    expect_stripes_equal_whole_frame([&](cv::Mat& d, cv::Range r) { k::bool3x3(src, d, b, r); });
  }
}

// A 3x3 kernel writing into its own input would read rows it has already overwritten.
TEST(NeighbourhoodArguments, OutputSharingMemoryWithTheInputIsRefused) {
  cv::RNG rng(kSeed);
  cv::Mat img = random_image(rng, {16, 12});
  const cv::Mat original = img.clone();
  EXPECT_THROW(k::conv3x3(img, img, k::smooth3x3()), k::KernelError);
  EXPECT_THROW(k::conv3x3(img, img, k::sobel_x3x3(), CV_16SC1), k::KernelError);
  cv::Mat overlapping = img.rowRange(2, 12);
  cv::Mat top = img.rowRange(0, 10);
  EXPECT_THROW(k::conv3x3(top, overlapping, k::smooth3x3(), CV_8UC1, cv::Range(0, 10)), k::KernelError);
  EXPECT_THROW(k::bool3x3(img, img, {k::erode_table(), 255, {}}), k::KernelError);
  EXPECT_TRUE(same_image(img, original)) << "a refused call must not have written anything";
  // A replicate border ignores the constant value, so a stale one is no error.
  cv::Mat out;
  EXPECT_NO_THROW(k::conv3x3(img, out, {{0, 0, 0, 0, 1, 0, 0, 0, 0}, 0, {k::BorderMode::replicate, 300}}));
}
