// Blob extraction in stripes (label_stripe + merge_stripes, kernels/blobs.hpp) and the two SIMD
// loops under all blob extraction (kernels/blob_runs.hpp).
//
// detail::find_runs and detail::weight_sums are held to trivial scalar loops for every row width
// 1..200 and some wide rows, random and special rows (all background, all foreground, alternating
// pixels, runs touching the row ends), rows at unaligned addresses surrounded by 0 and by 255, and
// rows placed against inaccessible pages, so that reading a byte outside the row crashes.
//
// Stripes: for random and shaped images, both connectivities and every way of cutting the rows into
// stripes (every subset of row borders for small heights, random cuts, one-row stripes, empty and
// clamped stripes), the merged blobs must be exactly those of extract_blobs on the whole frame
// (same order, every field, doubles bit for bit) and agree with cv::connectedComponentsWithStats.
// merge_stripes must refuse gaps, overlaps, other frames, other parameters and stripes it did not
// get from label_stripe.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "kernel_test_support.hpp"
#include "kernels/blob_runs.hpp"
#include "kernels/blobs.hpp"

#if defined(__unix__)
#include <sys/mman.h>
#include <unistd.h>
#define NEOPIPE_TEST_GUARD_PAGES 1
#endif

namespace k = neopipe::kernels;
namespace detail = neopipe::kernels::detail;
using neopipe::kernels::testing::checkerboard;
using neopipe::kernels::testing::comb;
using neopipe::kernels::testing::edge_blobs;
using neopipe::kernels::testing::frame_touching;
using neopipe::kernels::testing::identical_blobs;
using neopipe::kernels::testing::opencv_components;
using neopipe::kernels::testing::random_binary;
using neopipe::kernels::testing::random_image;
using neopipe::kernels::testing::roi_view;
using neopipe::kernels::testing::same_geometry;
using neopipe::kernels::testing::spiral;
using neopipe::kernels::testing::staircases;
using neopipe::kernels::testing::u_shape;

namespace {

constexpr std::uint64_t kSeed = 0x5eed'0004;
constexpr k::Connectivity kBothConnectivities[] = {k::Connectivity::four, k::Connectivity::eight};

std::string conn_name(k::Connectivity c) {
  return c == k::Connectivity::four ? "4-connected" : "8-connected";
}

std::string size_name(const cv::Mat& m) {
  return std::to_string(m.cols) + "x" + std::to_string(m.rows);
}

// =============================================================================================
// find_runs and weight_sums against scalar loops

/// Widths of the find_runs and weight_sums tests: every one up to 200 (below, at and across one
/// and four vectors of any target up to 64 lanes), and some wide rows.
std::vector<int> row_widths() {
  std::vector<int> widths;
  for (int w = 1; w <= 200; ++w) widths.push_back(w);
  for (int w : {255, 256, 257, 511, 1023, 1920, 4097}) widths.push_back(w);
  return widths;
}

/// The runs of (row[x] > t), one pixel at a time.
std::vector<detail::Run> scalar_runs(const std::uint8_t* row, int width, std::uint8_t t) {
  std::vector<detail::Run> runs;
  for (int x = 0; x < width;) {
    if (row[x] <= t) {
      ++x;
      continue;
    }
    const int xs = x;
    while (x < width && row[x] > t) ++x;
    runs.push_back({xs, x, 0});
  }
  return runs;
}

std::string runs_text(const std::vector<detail::Run>& runs) {
  std::ostringstream s;
  for (const auto& r : runs) s << " [" << r.xs << ", " << r.xe << ")";
  return s.str();
}

std::string row_text(const std::uint8_t* row, int width) {
  std::ostringstream s;
  for (int x = 0; x < std::min(width, 300); ++x) s << (x ? " " : "") << int{row[x]};
  if (width > 300) s << " ...";
  return s.str();
}

constexpr int kUntouchedLabel = -1234567;

/// find_runs equals the scalar runs; it leaves the labels alone and writes nothing past
/// max_runs(width) entries of `out`.
::testing::AssertionResult find_runs_matches_scalar(const std::uint8_t* row, int width, std::uint8_t t) {
  const auto room = static_cast<std::size_t>(detail::max_runs(width));
  constexpr std::size_t kSlack = 8;
  std::vector<detail::Run> out(room + kSlack, detail::Run{-7, -7, kUntouchedLabel});
  const int n = detail::find_runs(row, width, t, out.data());
  const auto expected = scalar_runs(row, width, t);
  const auto fail = [&] {
    return ::testing::AssertionFailure() << "width " << width << ", threshold " << int{t} << ", row "
                                         << row_text(row, width) << "\nexpected" << runs_text(expected);
  };
  if (n < 0 || static_cast<std::size_t>(n) > room) return fail() << "\nfind_runs returned " << n << " runs";
  std::vector<detail::Run> got(out.begin(), out.begin() + n);
  for (std::size_t i = room; i < out.size(); ++i) {
    if (out[i].xs != -7 || out[i].xe != -7 || out[i].label != kUntouchedLabel) {
      return fail() << "\nfind_runs wrote past max_runs(width) = " << room;
    }
  }
  if (got.size() != expected.size()) return fail() << "\ngot     " << runs_text(got);
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i].xs != expected[i].xs || got[i].xe != expected[i].xe) return fail() << "\ngot     " << runs_text(got);
    if (got[i].label != kUntouchedLabel) return fail() << "\nfind_runs changed the label of run " << i;
  }
  return ::testing::AssertionSuccess();
}

/// A row of alternating background (<= t) and foreground (> t) segments whose lengths are drawn
/// from 1..max_len, with random values on each side of the threshold. All background if t is 255.
std::vector<std::uint8_t> segmented_row(cv::RNG& rng, int width, std::uint8_t t, int max_len) {
  std::vector<std::uint8_t> row(static_cast<std::size_t>(width));
  bool fg = rng.uniform(0, 2) == 1 && t < 255;
  for (int x = 0; x < width;) {
    const int end = std::min(width, x + rng.uniform(1, max_len + 1));
    for (; x < end; ++x) {
      row[static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(fg ? rng.uniform(t + 1, 256) : rng.uniform(0, int{t} + 1));
    }
    fg = !fg && t < 255;
  }
  return row;
}

std::uint8_t random_threshold(cv::RNG& rng) {
  const int pick = rng.uniform(0, 6);
  if (pick == 0) return 0;
  if (pick == 1) return 254;
  if (pick == 2) return 255;
  return static_cast<std::uint8_t>(rng.uniform(0, 256));
}

/// A buffer with `row` copied at `offset`, everything else `fill`.
std::vector<std::uint8_t> embedded(const std::vector<std::uint8_t>& row, int offset, std::uint8_t fill) {
  std::vector<std::uint8_t> buf(row.size() + static_cast<std::size_t>(offset) + 80, fill);
  std::copy(row.begin(), row.end(), buf.begin() + offset);
  return buf;
}

TEST(FindRuns, RandomRowsOfEveryWidthMatchScalar) {
  cv::RNG rng(kSeed);
  for (int width : row_widths()) {
    for (int trial = 0; trial < 8; ++trial) {
      const std::uint8_t t = random_threshold(rng);
      constexpr int kMaxLens[] = {1, 3, 17, 70, 300};
      const int max_len = kMaxLens[trial % 5];
      std::vector<std::uint8_t> row;
      if (trial == 7) {
        row.resize(static_cast<std::size_t>(width));  // uniform noise: runs of any length, mostly short
        for (auto& v : row) v = static_cast<std::uint8_t>(rng.uniform(0, 256));
      } else {
        row = segmented_row(rng, width, t, max_len);
      }
      // At an unaligned address, among bytes that would be foreground and then background.
      const int offset = rng.uniform(0, 64);
      for (std::uint8_t fill : {std::uint8_t{255}, std::uint8_t{0}}) {
        const auto buf = embedded(row, offset, fill);
        ASSERT_TRUE(find_runs_matches_scalar(buf.data() + offset, width, t))
            << "offset " << offset << ", surrounded by " << int{fill};
      }
    }
  }
}

TEST(FindRuns, EveryOffsetAndSurroundingBytesGiveTheSameRuns) {
  cv::RNG rng(kSeed + 1);
  for (int width : {1, 2, 15, 16, 17, 31, 32, 33, 63, 64, 65, 127, 128, 129, 130, 200, 257}) {
    const auto t = static_cast<std::uint8_t>(random_threshold(rng) / 2);  // some foreground
    const auto row = segmented_row(rng, width, t, 9);
    for (int offset = 0; offset < 70; ++offset) {
      for (std::uint8_t fill : {std::uint8_t{255}, std::uint8_t{0}, std::uint8_t{static_cast<std::uint8_t>(t + 1)}}) {
        const auto buf = embedded(row, offset, fill);
        ASSERT_TRUE(find_runs_matches_scalar(buf.data() + offset, width, t))
            << "offset " << offset << ", surrounded by " << int{fill};
      }
    }
  }
}

TEST(FindRuns, ThresholdsZero254And255) {
  cv::RNG rng(kSeed + 2);
  for (int width : row_widths()) {
    // Values right at the thresholds: 0 vs 1 for t = 0, 254 vs 255 for t = 254.
    std::vector<std::uint8_t> low(static_cast<std::size_t>(width));
    std::vector<std::uint8_t> high(static_cast<std::size_t>(width));
    for (int x = 0; x < width; ++x) {
      const bool fg = rng.uniform(0, 3) != 0;
      low[static_cast<std::size_t>(x)] = fg ? 1 : 0;
      high[static_cast<std::size_t>(x)] = fg ? 255 : 254;
    }
    ASSERT_TRUE(find_runs_matches_scalar(low.data(), width, 0));
    ASSERT_TRUE(find_runs_matches_scalar(high.data(), width, 254));
    ASSERT_TRUE(find_runs_matches_scalar(high.data(), width, 255));  // nothing exceeds 255
    std::vector<detail::Run> out(static_cast<std::size_t>(detail::max_runs(width)));
    EXPECT_EQ(detail::find_runs(high.data(), width, 255, out.data()), 0);
  }
}

TEST(FindRuns, AllBackgroundAndAllForeground) {
  for (int width : row_widths()) {
    std::vector<detail::Run> out(static_cast<std::size_t>(detail::max_runs(width)));
    for (int t : {0, 1, 128, 254}) {
      const std::vector<std::uint8_t> bg(static_cast<std::size_t>(width), static_cast<std::uint8_t>(t));
      const std::vector<std::uint8_t> fg(static_cast<std::size_t>(width), static_cast<std::uint8_t>(t + 1));
      EXPECT_EQ(detail::find_runs(bg.data(), width, static_cast<std::uint8_t>(t), out.data()), 0)
          << "width " << width << ", threshold " << t;
      ASSERT_EQ(detail::find_runs(fg.data(), width, static_cast<std::uint8_t>(t), out.data()), 1)
          << "width " << width << ", threshold " << t;
      EXPECT_EQ(out[0].xs, 0);
      EXPECT_EQ(out[0].xe, width);
    }
    const std::vector<std::uint8_t> white(static_cast<std::size_t>(width), 255);
    EXPECT_EQ(detail::find_runs(white.data(), width, 255, out.data()), 0);
  }
}

TEST(FindRuns, AlternatingPixelsFillMaxRuns) {
  for (int width : row_widths()) {
    for (int first : {0, 1}) {
      std::vector<std::uint8_t> row(static_cast<std::size_t>(width));
      for (int x = 0; x < width; ++x) row[static_cast<std::size_t>(x)] = (x + first) % 2 == 1 ? 0 : 200;
      ASSERT_TRUE(find_runs_matches_scalar(row.data(), width, 100)) << "foreground at even x: " << (first == 0);
      std::vector<detail::Run> out(static_cast<std::size_t>(detail::max_runs(width)));
      const int n = detail::find_runs(row.data(), width, 100, out.data());
      EXPECT_EQ(n, first == 0 ? (width + 1) / 2 : width / 2) << "width " << width;
      // Foreground at both ends of an odd row: exactly max_runs(width), the room out must have.
      if (first == 0 && width % 2 == 1) {
        EXPECT_EQ(n, detail::max_runs(width)) << "width " << width;
      }
    }
  }
}

TEST(FindRuns, RunsTouchingTheRowEnds) {
  for (int width : row_widths()) {
    // One foreground pixel, then one background pixel, at every position (every position for the
    // narrow rows, the ends and vector borders for the wide ones).
    std::vector<int> positions;
    for (int p = 0; p < width; ++p) {
      if (width <= 200 || p < 130 || p >= width - 130) positions.push_back(p);
    }
    for (int p : positions) {
      std::vector<std::uint8_t> one(static_cast<std::size_t>(width), 0);
      one[static_cast<std::size_t>(p)] = 255;
      ASSERT_TRUE(find_runs_matches_scalar(one.data(), width, 0)) << "foreground pixel at " << p;
      std::vector<std::uint8_t> hole(static_cast<std::size_t>(width), 255);
      hole[static_cast<std::size_t>(p)] = 0;
      ASSERT_TRUE(find_runs_matches_scalar(hole.data(), width, 0)) << "background pixel at " << p;
    }
    // Foreground at both ends only, and prefixes and suffixes of every length.
    std::vector<std::uint8_t> ends(static_cast<std::size_t>(width), 0);
    ends.front() = 255;
    ends.back() = 255;
    ASSERT_TRUE(find_runs_matches_scalar(ends.data(), width, 0));
    for (int len : {1, 2, 31, 32, 33, 64, 65, 128, 129, width - 1}) {
      if (len < 1 || len > width) continue;
      std::vector<std::uint8_t> prefix(static_cast<std::size_t>(width), 0);
      std::fill(prefix.begin(), prefix.begin() + len, 255);
      ASSERT_TRUE(find_runs_matches_scalar(prefix.data(), width, 0)) << "prefix of " << len;
      std::vector<std::uint8_t> suffix(static_cast<std::size_t>(width), 0);
      std::fill(suffix.end() - len, suffix.end(), 255);
      ASSERT_TRUE(find_runs_matches_scalar(suffix.data(), width, 0)) << "suffix of " << len;
    }
  }
}

/// weight_sums equals the scalar sums.
::testing::AssertionResult weight_sums_match_scalar(const std::uint8_t* row, int xs, int xe) {
  detail::WeightSums expected;
  for (int x = xs; x < xe; ++x) {
    expected.sw += row[x];
    expected.swx += std::int64_t{row[x]} * x;
  }
  const detail::WeightSums got = detail::weight_sums(row, xs, xe);
  if (got.sw == expected.sw && got.swx == expected.swx) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "run [" << xs << ", " << xe << "): sw " << got.sw << ", swx " << got.swx
                                       << "; expected sw " << expected.sw << ", swx " << expected.swx;
}

TEST(WeightSums, EveryLengthUpTo300AtManyOffsetsMatchesScalar) {
  cv::RNG rng(kSeed + 3);
  std::vector<std::uint8_t> buf(1024);
  for (auto& v : buf) v = static_cast<std::uint8_t>(rng.uniform(0, 256));
  std::vector<std::uint8_t> white(1024, 255);
  for (int base : {0, 1, 7, 32, 33}) {  // alignment of the row itself
    for (int xs : {0, 1, 2, 3, 15, 16, 17, 31, 32, 33, 63, 64, 65, 100, 255, 400}) {
      for (int len = 0; len <= 300; ++len) {
        ASSERT_TRUE(weight_sums_match_scalar(buf.data() + base, xs, xs + len)) << "row at +" << base;
        ASSERT_TRUE(weight_sums_match_scalar(white.data() + base, xs, xs + len)) << "all 255, row at +" << base;
      }
    }
  }
}

TEST(WeightSums, NothingOutsideTheRunMatters) {
  cv::RNG rng(kSeed + 4);
  for (int len = 0; len <= 300; ++len) {
    const int xs = rng.uniform(0, 90);
    std::vector<std::uint8_t> zeros(static_cast<std::size_t>(xs + len + 100), 0);
    std::vector<std::uint8_t> whites(zeros.size(), 255);
    for (int x = xs; x < xs + len; ++x) {
      zeros[static_cast<std::size_t>(x)] = whites[static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(rng.uniform(0, 256));
    }
    const auto a = detail::weight_sums(zeros.data(), xs, xs + len);
    const auto b = detail::weight_sums(whites.data(), xs, xs + len);
    EXPECT_EQ(a.sw, b.sw) << "length " << len;
    EXPECT_EQ(a.swx, b.swx) << "length " << len;
    ASSERT_TRUE(weight_sums_match_scalar(zeros.data(), xs, xs + len));
  }
}

TEST(WeightSums, LongRunsOfMaximumWeight) {
  // The vector loop sums blocks of up to 2048 vectors in int32 lanes: runs that fill one block with
  // 255s (16, 32 or 64 lanes), runs of several blocks, and runs of 1.5 million pixels, which would
  // overflow int32 sums of w * offset on any target (16 to 64 lanes) if they were not split into
  // blocks. Far from x = 0 too.
  constexpr int kMaxLen = 1'500'000;
  constexpr int kFar = 1 << 20;
  std::vector<std::uint8_t> white(static_cast<std::size_t>(kFar + kMaxLen + 64), 255);
  for (int len :
       {10000, 2048 * 16 - 1, 2048 * 16, 2048 * 16 + 1, 2048 * 32 - 1, 2048 * 32, 2048 * 32 + 1, 2048 * 32 + 31,
        2048 * 64 - 1, 2048 * 64, 2048 * 64 + 1, 2048 * 64 + 63, 2048 * 64 * 2, 600'001, kMaxLen}) {
    for (int xs : {0, 1, 31, 12345, kFar}) {
      for (int base : {0, 3}) {
        const std::uint8_t* row = white.data() + base;
        const auto got = detail::weight_sums(row, xs, xs + len);
        const std::int64_t n = len;
        const std::int64_t first = xs;
        EXPECT_EQ(got.sw, 255 * n) << "length " << len << " from " << xs;
        EXPECT_EQ(got.swx, 255 * (n * first + n * (n - 1) / 2)) << "length " << len << " from " << xs;
      }
    }
  }
  // Random weights over long runs.
  cv::RNG rng(kSeed + 5);
  std::vector<std::uint8_t> noise(static_cast<std::size_t>(kMaxLen + 200));
  for (auto& v : noise) v = static_cast<std::uint8_t>(rng.uniform(0, 256));
  for (int len : {10000, 2048 * 32 + 5, 2048 * 64 + 17, kMaxLen}) {
    for (int xs : {0, 1, 77}) ASSERT_TRUE(weight_sums_match_scalar(noise.data(), xs, xs + len));
  }
}

#ifdef NEOPIPE_TEST_GUARD_PAGES

/// Readable, writable bytes [begin(), end()) between two inaccessible pages: touching a byte just
/// before begin() or at end() crashes.
class GuardedBytes {
 public:
  explicit GuardedBytes(std::size_t size) {
    page_ = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    data_ = (size + page_ - 1) / page_ * page_;
    total_ = data_ + 2 * page_;
    void* p = mmap(nullptr, total_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error("mmap failed");
    base_ = static_cast<std::uint8_t*>(p);
    if (mprotect(base_, page_, PROT_NONE) != 0 || mprotect(base_ + page_ + data_, page_, PROT_NONE) != 0) {
      munmap(base_, total_);
      throw std::runtime_error("mprotect failed");
    }
  }
  GuardedBytes(const GuardedBytes&) = delete;
  GuardedBytes& operator=(const GuardedBytes&) = delete;
  ~GuardedBytes() { munmap(base_, total_); }

  std::uint8_t* begin() const { return base_ + page_; }
  std::uint8_t* end() const { return base_ + page_ + data_; }
  std::size_t page() const { return page_; }

 private:
  std::uint8_t* base_ = nullptr;
  std::size_t page_ = 0;
  std::size_t data_ = 0;
  std::size_t total_ = 0;
};

TEST(FindRuns, ReadsNothingOutsideTheRow) {
  // A row against an inaccessible page on either side: a read past either end would crash.
  cv::RNG rng(kSeed + 6);
  GuardedBytes bytes(8192);
  for (int width : row_widths()) {
    for (std::uint8_t t : {std::uint8_t{0}, std::uint8_t{100}, std::uint8_t{254}}) {
      const auto row = segmented_row(rng, width, t, 40);
      std::uint8_t* at_end = bytes.end() - width;
      std::copy(row.begin(), row.end(), at_end);
      ASSERT_TRUE(find_runs_matches_scalar(at_end, width, t)) << "row ending at a guard page";
      std::copy(row.begin(), row.end(), bytes.begin());
      ASSERT_TRUE(find_runs_matches_scalar(bytes.begin(), width, t)) << "row starting at a guard page";
    }
  }
}

TEST(WeightSums, ReadsOnlyTheRun) {
  cv::RNG rng(kSeed + 7);
  GuardedBytes bytes(2048 * 64 + 4096);
  for (auto* p = bytes.begin(); p != bytes.end(); ++p) *p = static_cast<std::uint8_t>(rng.uniform(0, 256));
  const int size = static_cast<int>(bytes.end() - bytes.begin());
  for (int len = 0; len <= 300; ++len) {
    for (int xs : {0, 1, 5, 40}) {
      // The run ends at the guard page after it (the row starts before the run, inside the buffer).
      ASSERT_TRUE(weight_sums_match_scalar(bytes.end() - xs - len, xs, xs + len)) << "run ending at a guard page";
      // The run starts at the guard page before it; `row` points into that page, which is never read.
      ASSERT_TRUE(weight_sums_match_scalar(bytes.begin() - xs, xs, xs + len)) << "run starting at a guard page";
    }
  }
  for (int len : {2048 * 32 + 7, 2048 * 64 + 9, size}) {
    ASSERT_TRUE(weight_sums_match_scalar(bytes.end() - len - 3, 3, len + 3));
    ASSERT_TRUE(weight_sums_match_scalar(bytes.begin() - 3, 3, len + 3));
  }
}

TEST(WeightSums, RowWidthFormReadsOnlyTheRowAndMatchesScalarForEveryRun) {
  // weight_sums(row, width, xs, xe) may read the whole row but nothing outside it: rows of every
  // width up to 100 sit against a guard page on either side, and every run in them is summed.
  cv::RNG rng(kSeed + 8);
  GuardedBytes bytes(4096);
  for (auto* p = bytes.begin(); p != bytes.end(); ++p) *p = static_cast<std::uint8_t>(rng.uniform(0, 256));
  for (int width = 1; width <= 100; ++width) {
    for (const std::uint8_t* row : {bytes.begin(), bytes.end() - width}) {
      for (int xs = 0; xs < width; ++xs) {
        for (int xe = xs; xe <= width; ++xe) {
          detail::WeightSums expected;
          for (int x = xs; x < xe; ++x) {
            expected.sw += row[x];
            expected.swx += std::int64_t{row[x]} * x;
          }
          const detail::WeightSums got = detail::weight_sums(row, width, xs, xe);
          ASSERT_TRUE(got.sw == expected.sw && got.swx == expected.swx)
              << "width " << width << ", run [" << xs << ", " << xe << "): sw " << got.sw << ", swx " << got.swx
              << "; expected " << expected.sw << ", " << expected.swx;
        }
      }
    }
  }
}

#endif  // NEOPIPE_TEST_GUARD_PAGES

// =============================================================================================
// Stripes

using Stripes = std::vector<cv::Range>;

std::string stripes_text(const Stripes& stripes) {
  std::ostringstream s;
  for (const auto& r : stripes) s << " [" << r.start << ", " << r.end << ")";
  return s.str();
}

Stripes stripes_from_cuts(const std::vector<int>& cuts) {
  Stripes s;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) s.emplace_back(cuts[i], cuts[i + 1]);
  return s;
}

/// Every way of cutting `height` rows into non-empty stripes: one for each subset of the height - 1
/// borders between rows.
std::vector<Stripes> every_cut(int height) {
  std::vector<Stripes> all;
  for (unsigned mask = 0; mask < (1U << (height - 1)); ++mask) {
    std::vector<int> cuts{0};
    for (int y = 1; y < height; ++y) {
      if ((mask >> (y - 1)) & 1U) cuts.push_back(y);
    }
    cuts.push_back(height);
    all.push_back(stripes_from_cuts(cuts));
  }
  return all;
}

/// The same cut with empty stripes added (at the start, at the end and at a random border, some
/// of them outside the frame) and its outer stripes reaching beyond the frame: all clamped away.
Stripes with_empty_stripes(cv::RNG& rng, Stripes s, int height) {
  const int at = rng.uniform(0, static_cast<int>(s.size()) + 1);
  const int y = at == 0 ? 0 : s[static_cast<std::size_t>(at - 1)].end;
  s.insert(s.begin() + at, cv::Range(y, y));
  s.front().start = -3;
  s.back().end = height + 9;
  s.insert(s.begin(), cv::Range(-5, -1));
  s.emplace_back(height + 1, height + 4);
  s.emplace_back(height, height);
  return s;
}

/// Random cuts; cut points may repeat, which makes empty stripes.
Stripes random_cut(cv::RNG& rng, int height) {
  const int n = rng.uniform(1, std::min(height, 16) + 1);
  std::vector<int> cuts{0, height};
  for (int i = 1; i < n; ++i) cuts.push_back(rng.uniform(0, height + 1));
  std::sort(cuts.begin(), cuts.end());
  return stripes_from_cuts(cuts);
}

/// The cuts to try for a frame of `height` rows: every one (with and without empty stripes) up to
/// 8 rows; beyond that one-row stripes, the whole frame, each single border and random cuts.
std::vector<Stripes> cuts_to_try(cv::RNG& rng, int height, int random_cuts = 24) {
  std::vector<Stripes> cuts;
  if (height <= 8) {
    for (const auto& s : every_cut(height)) {
      cuts.push_back(s);
      cuts.push_back(with_empty_stripes(rng, s, height));
    }
    cuts.push_back({cv::Range::all()});
    return cuts;
  }
  std::vector<int> rows(static_cast<std::size_t>(height) + 1);
  for (int y = 0; y <= height; ++y) rows[static_cast<std::size_t>(y)] = y;
  cuts.push_back(stripes_from_cuts(rows));
  cuts.push_back(with_empty_stripes(rng, stripes_from_cuts(rows), height));
  cuts.push_back({cv::Range::all()});
  for (int y = 1; y < height; y += std::max(1, height / 24)) cuts.push_back({cv::Range(0, y), cv::Range(y, height)});
  for (int i = 0; i < random_cuts; ++i) {
    cuts.push_back(random_cut(rng, height));
    if (i % 4 == 0) cuts.push_back(with_empty_stripes(rng, random_cut(rng, height), height));
  }
  return cuts;
}

/// Labels each of `stripes` (last first: they are independent) and merges them.
std::vector<k::Blob> blobs_in_stripes(const cv::Mat& src, const k::BlobParams& p, const cv::Mat& weights,
                                      const Stripes& stripes) {
  std::vector<k::BlobStripe> labelled(stripes.size());
  for (std::size_t i = stripes.size(); i-- > 0;) labelled[i] = k::label_stripe(src, p, weights, stripes[i]);
  return k::merge_stripes(std::move(labelled), p);
}

/// For each cut in `cuts`, the merged stripes give exactly extract_blobs' blobs on the whole frame,
/// and OpenCV's areas, boxes and centroids.
void expect_stripes_give_whole_frame_blobs(const cv::Mat& src, const k::BlobParams& p, const cv::Mat& weights,
                                           const std::vector<Stripes>& cuts) {
  SCOPED_TRACE(size_name(src) + ", threshold " + std::to_string(p.threshold) + ", " + conn_name(p.connectivity) +
               (weights.empty() ? "" : ", separate weights"));
  const auto whole = k::extract_blobs(src, p, weights);
  const auto opencv = opencv_components(src, p.threshold, p.connectivity).blobs;
  ASSERT_EQ(whole.size(), opencv.size());
  for (const auto& stripes : cuts) {
    const auto merged = blobs_in_stripes(src, p, weights, stripes);
    ASSERT_TRUE(identical_blobs(merged, whole)) << "stripes" << stripes_text(stripes);
    for (std::size_t i = 0; i < merged.size(); ++i) {
      ASSERT_TRUE(same_geometry(merged[i], opencv[i])) << "blob " << i << ", stripes" << stripes_text(stripes);
    }
  }
}

void expect_every_cut_gives_whole_frame_blobs(cv::RNG& rng, const cv::Mat& src, int threshold,
                                              const cv::Mat& weights = cv::Mat()) {
  const auto cuts = cuts_to_try(rng, src.rows);
  for (k::Connectivity c : kBothConnectivities) {
    expect_stripes_give_whole_frame_blobs(src, {threshold, c}, weights, cuts);
  }
}

int merged_count(const cv::Mat& src, k::Connectivity c, const Stripes& stripes) {
  return static_cast<int>(blobs_in_stripes(src, {0, c}, cv::Mat(), stripes).size());
}

Stripes one_row_stripes(int height) {
  Stripes s;
  for (int y = 0; y < height; ++y) s.emplace_back(y, y + 1);
  return s;
}

/// Large irregular blobs with holes, bays and long runs: smooth noise.
cv::Mat smooth_noise(cv::RNG& rng, cv::Size size, int cell) {
  cv::Mat coarse = random_image(rng, {std::max(2, size.width / cell), std::max(2, size.height / cell)});
  cv::Mat fine;
  cv::resize(coarse, fine, size, 0, 0, cv::INTER_LINEAR);
  return fine;
}

/// A path down column 0, along the bottom row to column 2, up column 2, along the top row to
/// column 4, and so on: one component whose columns are separate pieces in every stripe that holds
/// neither the top nor the bottom row, so it crosses every stripe border `columns` times.
cv::Mat vertical_snake(int columns, int height) {
  cv::Mat m(height, 2 * columns - 1, CV_8UC1, cv::Scalar(0));
  for (int c = 0; c < columns; ++c) {
    m.col(2 * c).setTo(255);
    if (c + 1 < columns) m.at<std::uint8_t>(c % 2 == 0 ? height - 1 : 0, 2 * c + 1) = 255;
  }
  return m;
}

TEST(BlobStripes, RandomBinaryImagesInEveryCut) {
  cv::RNG rng(kSeed + 10);
  const cv::Size sizes[] = {{1, 1},  {7, 1},  {200, 1}, {1, 2},   {1, 8},   {1, 37},   {2, 2},    {3, 3},   {5, 4},
                            {13, 7}, {29, 8}, {67, 8},  {130, 6}, {64, 48}, {129, 67}, {257, 33}, {31, 100}};
  for (const cv::Size size : sizes) {
    for (double density : {0.3, 0.5, 0.7}) {
      SCOPED_TRACE("density " + std::to_string(density));
      expect_every_cut_gives_whole_frame_blobs(rng, random_binary(rng, size, density), 0);
    }
  }
}

TEST(BlobStripes, GrayImagesWithThresholdsAndWeights) {
  cv::RNG rng(kSeed + 11);
  const cv::Size sizes[] = {{1, 7}, {9, 1}, {11, 8}, {40, 5}, {73, 29}, {100, 64}};
  for (const cv::Size size : sizes) {
    const cv::Mat src = random_image(rng, size);
    const cv::Mat weights = random_image(rng, size);
    cv::Mat sparse_weights = weights.clone();
    sparse_weights.setTo(0, random_binary(rng, size, 0.8));
    const cv::Mat zero_weights(size, CV_8UC1, cv::Scalar(0));
    for (int t : {-1, 0, 1, 77, 128, 200, 254, 255}) {
      SCOPED_TRACE("threshold " + std::to_string(t));
      expect_every_cut_gives_whole_frame_blobs(rng, src, t);
      expect_every_cut_gives_whole_frame_blobs(rng, src, t, weights);
    }
    expect_every_cut_gives_whole_frame_blobs(rng, src, 100, sparse_weights);
    expect_every_cut_gives_whole_frame_blobs(rng, src, 100, zero_weights);
  }
}

TEST(BlobStripes, LargeIrregularBlobsAcrossManyStripes) {
  cv::RNG rng(kSeed + 12);
  for (const cv::Size size : {cv::Size(8, 8), cv::Size(150, 8), cv::Size(640, 120), cv::Size(97, 301)}) {
    const cv::Mat src = smooth_noise(rng, size, 9);
    SCOPED_TRACE(size_name(src));
    for (int t : {90, 128, 170}) expect_every_cut_gives_whole_frame_blobs(rng, src, t, random_image(rng, size));
  }
}

TEST(BlobStripes, WeightsDifferentFromSrcAreUsed) {
  cv::RNG rng(kSeed + 13);
  const cv::Mat src = random_binary(rng, {60, 40}, 0.6);
  const cv::Mat weights = random_image(rng, src.size());
  for (k::Connectivity c : kBothConnectivities) {
    const k::BlobParams p{0, c};
    for (const auto& stripes : cuts_to_try(rng, src.rows, 8)) {
      const auto with = blobs_in_stripes(src, p, weights, stripes);
      ASSERT_TRUE(identical_blobs(with, k::extract_blobs(src, p, weights))) << "stripes" << stripes_text(stripes);
      ASSERT_TRUE(identical_blobs(blobs_in_stripes(src, p, cv::Mat(), stripes), k::extract_blobs(src, p)));
      // src is 0/255, so its own weights give the plain centroid; the separate ones must not.
      ASSERT_FALSE(identical_blobs(with, k::extract_blobs(src, p)));
    }
  }
}

TEST(BlobStripes, RoiViewsOfSrcAndWeights) {
  cv::RNG rng(kSeed + 14);
  for (const cv::Size size : {cv::Size(17, 11), cv::Size(1, 11), cv::Size(17, 1), cv::Size(40, 7)}) {
    // Foreground around the views would join their blobs if anything read past them.
    const cv::Mat src = roi_view([&](cv::Size s) { return random_binary(rng, s, 0.55); }, size);
    const cv::Mat weights = roi_view([&](cv::Size s) { return random_image(rng, s); }, size);
    ASSERT_FALSE(src.isContinuous() && size.height > 1);
    SCOPED_TRACE(size_name(src) + " views");
    expect_every_cut_gives_whole_frame_blobs(rng, src, 0, weights);
    for (k::Connectivity c : kBothConnectivities) {
      EXPECT_TRUE(identical_blobs(blobs_in_stripes(src, {0, c}, weights, one_row_stripes(size.height)),
                                  k::extract_blobs(src.clone(), {0, c}, weights.clone())));
    }
  }
}

TEST(BlobStripes, VerticalSnakeCrossesEveryBorderManyTimes) {
  cv::RNG rng(kSeed + 15);
  for (const auto& [columns, height] : {std::pair{5, 8}, std::pair{9, 60}, std::pair{1, 8}, std::pair{3, 2}}) {
    const cv::Mat m = vertical_snake(columns, height);
    SCOPED_TRACE("snake of " + std::to_string(columns) + " columns, " + std::to_string(height) + " rows");
    expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
    for (k::Connectivity c : kBothConnectivities) {
      const auto blobs = blobs_in_stripes(m, {0, c}, cv::Mat(), one_row_stripes(height));
      ASSERT_EQ(blobs.size(), 1U);
      EXPECT_EQ(blobs[0].area, std::int64_t{columns} * height + columns - 1);
      EXPECT_EQ(blobs[0].width, m.cols);
      EXPECT_EQ(blobs[0].height, height);
      if (height >= 3) {
        // Inside, every column is a piece of its own.
        EXPECT_EQ(k::label_stripe(m, {0, c}, cv::Mat(), {1, height - 1}).pieces(), static_cast<std::size_t>(columns));
      }
    }
    // Turned on its side and upside down.
    cv::Mat turned;
    cv::rotate(m, turned, cv::ROTATE_90_CLOCKWISE);
    expect_every_cut_gives_whole_frame_blobs(rng, turned, 0);
    cv::flip(m, turned, 0);
    expect_every_cut_gives_whole_frame_blobs(rng, turned, 0);
  }
}

TEST(BlobStripes, SpiralsAndCombs) {
  cv::RNG rng(kSeed + 16);
  for (int n : {5, 8, 21, 40}) {
    const cv::Mat m = spiral(n);
    SCOPED_TRACE("spiral " + std::to_string(n));
    expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
    for (int code : {cv::ROTATE_90_CLOCKWISE, cv::ROTATE_180, cv::ROTATE_90_COUNTERCLOCKWISE}) {
      cv::Mat r;
      cv::rotate(m, r, code);
      expect_every_cut_gives_whole_frame_blobs(rng, r, 0);
    }
    for (k::Connectivity c : kBothConnectivities) EXPECT_EQ(merged_count(m, c, one_row_stripes(n)), 1);
  }
  for (bool ragged : {false, true}) {
    const cv::Mat m = comb(12, 20, ragged);
    cv::Mat upside_down;
    cv::flip(m, upside_down, 0);
    for (const cv::Mat& img : {m, upside_down}) {
      expect_every_cut_gives_whole_frame_blobs(rng, img, 0);
      for (k::Connectivity c : kBothConnectivities) EXPECT_EQ(merged_count(img, c, one_row_stripes(img.rows)), 1);
    }
  }
}

TEST(BlobStripes, UShapeArmsArePiecesInOneStripeAndJoinInAnother) {
  cv::RNG rng(kSeed + 17);
  const cv::Mat u = u_shape();  // inner U: arms x 6 and 9, rows 1..9; outer U: arms x 3 and 12, rows 2..12
  for (k::Connectivity c : kBothConnectivities) {
    SCOPED_TRACE(conn_name(c));
    const k::BlobParams p{0, c};
    // Above row 9 all four arms are apart; above row 12 only the outer U's two.
    EXPECT_EQ(k::label_stripe(u, p, cv::Mat(), {0, 9}).pieces(), 4U);
    EXPECT_EQ(k::label_stripe(u, p, cv::Mat(), {0, 12}).pieces(), 3U);
    EXPECT_EQ(k::label_stripe(u, p, cv::Mat(), {9, 15}).pieces(), 2U);
    EXPECT_EQ(k::label_stripe(u, p, cv::Mat(), {12, 15}).pieces(), 1U);
    EXPECT_EQ(k::label_stripe(u, p, cv::Mat(), cv::Range::all()).pieces(), 2U);
    for (const Stripes& s : {Stripes{{0, 9}, {9, 15}}, Stripes{{0, 12}, {12, 15}}, Stripes{{0, 5}, {5, 10}, {10, 15}},
                             one_row_stripes(u.rows)}) {
      const auto blobs = blobs_in_stripes(u, p, cv::Mat(), s);
      ASSERT_EQ(blobs.size(), 2U) << "stripes" << stripes_text(s);
      EXPECT_EQ(blobs[0].y0, 1);  // the inner U starts higher: it comes first
      EXPECT_EQ(blobs[1].y0, 2);
      EXPECT_TRUE(identical_blobs(blobs, k::extract_blobs(u, p)));
    }
  }
  expect_every_cut_gives_whole_frame_blobs(rng, u, 0);
  // Upside down: the arms join in the upper stripe and part in the lower one.
  cv::Mat n;
  cv::flip(u, n, 0);
  EXPECT_EQ(k::label_stripe(n, {}, cv::Mat(), {6, 15}).pieces(), 4U);
  expect_every_cut_gives_whole_frame_blobs(rng, n, 0);
  // Side by side with mirrored copies, so that pieces of several blobs interleave in a stripe.
  cv::Mat mirrored;
  cv::flip(u, mirrored, 1);
  cv::Mat pair;
  cv::hconcat(std::vector<cv::Mat>{u, mirrored, n}, pair);
  expect_every_cut_gives_whole_frame_blobs(rng, pair, 0);
}

TEST(BlobStripes, DiagonalContactAcrossAStripeBorderJoinsOnlyUnderEightConnectivity) {
  cv::RNG rng(kSeed + 24);
  // Row 1 holds [4, 7); row 2, below the border between the stripes [0, 2) and [2, 4), one of these.
  struct Below {
    int xs, xe;
    bool overlaps;  // joined under both connectivities
    bool diagonal;  // joined under 8-connectivity only
  };
  const Below cases[] = {{7, 9, false, true},  {1, 4, false, true}, {8, 10, false, false}, {0, 3, false, false},
                         {6, 8, true, false},  {2, 5, true, false}, {0, 12, true, false},  {5, 6, true, false},
                         {7, 12, false, true}, {0, 4, false, true}, {9, 12, false, false}, {4, 7, true, false}};
  for (const auto& b : cases) {
    for (bool flipped : {false, true}) {
      cv::Mat m(4, 12, CV_8UC1, cv::Scalar(0));
      m(cv::Range(1, 2), cv::Range(4, 7)).setTo(255);
      m(cv::Range(2, 3), cv::Range(b.xs, b.xe)).setTo(255);
      if (flipped) cv::flip(m, m, 0);  // the run in the lower stripe comes first
      SCOPED_TRACE("run below [" + std::to_string(b.xs) + ", " + std::to_string(b.xe) + ")" +
                   (flipped ? ", upside down" : ""));
      for (k::Connectivity c : kBothConnectivities) {
        const int expected = b.overlaps || (b.diagonal && c == k::Connectivity::eight) ? 1 : 2;
        EXPECT_EQ(merged_count(m, c, {{0, 2}, {2, 4}}), expected) << conn_name(c);
        EXPECT_EQ(merged_count(m, c, one_row_stripes(4)), expected) << conn_name(c);
        EXPECT_EQ(merged_count(m, c, {cv::Range::all()}), expected) << conn_name(c);
      }
      expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
    }
  }
}

TEST(BlobStripes, DiagonalContactsAtTheFrameEdges) {
  cv::RNG rng(kSeed + 18);
  // Single pixels touching corner to corner at the left and right edges, across a border.
  cv::Mat left(2, 5, CV_8UC1, cv::Scalar(0));
  left.at<std::uint8_t>(0, 0) = 255;
  left.at<std::uint8_t>(1, 1) = 255;
  cv::Mat right(2, 5, CV_8UC1, cv::Scalar(0));
  right.at<std::uint8_t>(0, 4) = 255;
  right.at<std::uint8_t>(1, 3) = 255;
  cv::Mat anti(2, 2, CV_8UC1, cv::Scalar(0));
  anti.at<std::uint8_t>(0, 1) = 255;
  anti.at<std::uint8_t>(1, 0) = 255;
  for (const cv::Mat& m : {left, right, anti}) {
    EXPECT_EQ(merged_count(m, k::Connectivity::eight, {{0, 1}, {1, 2}}), 1);
    EXPECT_EQ(merged_count(m, k::Connectivity::four, {{0, 1}, {1, 2}}), 2);
    expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
  }
  // Staircases and checkerboards: every row border is a diagonal contact.
  for (int n : {8, 17}) {
    const cv::Mat one = staircases(n, false);
    const cv::Mat x = staircases(n, true);
    EXPECT_EQ(merged_count(one, k::Connectivity::eight, one_row_stripes(n)), 1);
    EXPECT_EQ(merged_count(one, k::Connectivity::four, one_row_stripes(n)), n);
    EXPECT_EQ(merged_count(x, k::Connectivity::eight, one_row_stripes(n)), 1);
    expect_every_cut_gives_whole_frame_blobs(rng, one, 0);
    expect_every_cut_gives_whole_frame_blobs(rng, x, 0);
  }
  for (const cv::Size size : {cv::Size(2, 2), cv::Size(1, 8), cv::Size(8, 1), cv::Size(9, 8), cv::Size(31, 17)}) {
    const cv::Mat m = checkerboard(size);
    SCOPED_TRACE("checkerboard " + size_name(m));
    EXPECT_EQ(merged_count(m, k::Connectivity::four, one_row_stripes(size.height)), cv::countNonZero(m));
    if (size.width > 1 && size.height > 1) {
      EXPECT_EQ(merged_count(m, k::Connectivity::eight, one_row_stripes(size.height)), 1);
    }
    expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
  }
}

TEST(BlobStripes, ComponentsTouchingTheFrameBorder) {
  cv::RNG rng(kSeed + 19);
  for (const cv::Size size : {cv::Size(20, 15), cv::Size(9, 8), cv::Size(9, 9)}) {
    for (const cv::Mat& m : {frame_touching(size), edge_blobs(size)})
      expect_every_cut_gives_whole_frame_blobs(rng, m, 0);
    // The whole frame foreground, by value and by threshold -1.
    const cv::Mat white(size, CV_8UC1, cv::Scalar(255));
    expect_every_cut_gives_whole_frame_blobs(rng, white, 0);
    const cv::Mat gray = random_image(rng, size);
    expect_every_cut_gives_whole_frame_blobs(rng, gray, -1);
    for (k::Connectivity c : kBothConnectivities) {
      const auto blobs = blobs_in_stripes(gray, {-1, c}, cv::Mat(), one_row_stripes(size.height));
      ASSERT_EQ(blobs.size(), 1U);
      EXPECT_EQ(blobs[0].area, size.area());
      EXPECT_EQ(blobs[0].width, size.width);
      EXPECT_EQ(blobs[0].height, size.height);
      EXPECT_TRUE(blobs_in_stripes(white, {255, c}, cv::Mat(), one_row_stripes(size.height)).empty());
    }
  }
  // A ring along the frame edges, cut so that its sides are two pieces in every middle stripe.
  const cv::Mat ring = frame_touching({20, 15});
  for (k::Connectivity c : kBothConnectivities) {
    const auto blobs = blobs_in_stripes(ring, {0, c}, cv::Mat(), {{0, 5}, {5, 10}, {10, 15}});
    ASSERT_FALSE(blobs.empty());
    EXPECT_EQ(blobs[0].x0, 0);
    EXPECT_EQ(blobs[0].y0, 0);
    EXPECT_EQ(blobs[0].width, 20);
    EXPECT_EQ(blobs[0].height, 15);
  }
}

TEST(BlobStripes, StripeRowsAreClampedAndPiecesCounted) {
  cv::RNG rng(kSeed + 20);
  const cv::Mat src = random_binary(rng, {30, 12}, 0.5);
  const k::BlobParams p{};
  const k::BlobStripe none;
  EXPECT_TRUE(none.rows().empty());
  EXPECT_EQ(none.pieces(), 0U);
  EXPECT_EQ(k::label_stripe(src, p, cv::Mat(), cv::Range::all()).rows(), cv::Range(0, 12));
  EXPECT_EQ(k::label_stripe(src, p, cv::Mat(), {-3, 4}).rows(), cv::Range(0, 4));
  EXPECT_EQ(k::label_stripe(src, p, cv::Mat(), {5, 40}).rows(), cv::Range(5, 12));
  EXPECT_TRUE(k::label_stripe(src, p, cv::Mat(), {13, 20}).rows().empty());
  EXPECT_TRUE(k::label_stripe(src, p, cv::Mat(), {-9, -2}).rows().empty());
  EXPECT_TRUE(k::label_stripe(src, p, cv::Mat(), {7, 3}).rows().empty());
  EXPECT_EQ(k::label_stripe(src, p, cv::Mat(), {7, 7}).pieces(), 0U);
  EXPECT_EQ(k::label_stripe(src, p, cv::Mat(), {13, 20}).pieces(), 0U);
  for (k::Connectivity c : kBothConnectivities) {
    const k::BlobParams q{0, c};
    const std::size_t blobs = k::extract_blobs(src, q).size();
    EXPECT_EQ(k::label_stripe(src, q, cv::Mat(), cv::Range::all()).pieces(), blobs);
    // Each one-row stripe has a piece per run; there are at least as many pieces as blobs.
    std::size_t pieces = 0;
    for (int y = 0; y < src.rows; ++y) {
      const auto runs = scalar_runs(src.ptr<std::uint8_t>(y), src.cols, 0);
      const k::BlobStripe s = k::label_stripe(src, q, cv::Mat(), {y, y + 1});
      EXPECT_EQ(s.pieces(), runs.size()) << "row " << y;
      pieces += s.pieces();
    }
    EXPECT_GE(pieces, blobs);
  }
}

TEST(BlobStripes, StripesCanBeCopiedAndMoved) {
  cv::RNG rng(kSeed + 21);
  const cv::Mat src = random_binary(rng, {50, 20}, 0.55);
  const k::BlobParams p{0, k::Connectivity::eight};
  std::vector<k::BlobStripe> stripes{k::label_stripe(src, p, cv::Mat(), {0, 7}),
                                     k::label_stripe(src, p, cv::Mat(), {7, 8}),
                                     k::label_stripe(src, p, cv::Mat(), {8, 20})};
  const auto expected = k::extract_blobs(src, p);
  const std::vector<k::BlobStripe> copy = stripes;
  EXPECT_TRUE(identical_blobs(k::merge_stripes(copy, p), expected));
  EXPECT_TRUE(identical_blobs(k::merge_stripes(copy, p), expected));  // merging did not change the copy
  k::BlobStripe moved = std::move(stripes[1]);
  stripes[1] = moved;
  EXPECT_TRUE(identical_blobs(k::merge_stripes(std::move(stripes), p), expected));
}

// =============================================================================================
// merge_stripes and label_stripe errors

TEST(BlobStripes, MergeRefusesGapsOverlapsAndMissingRows) {
  cv::RNG rng(kSeed + 22);
  const cv::Mat src = random_binary(rng, {16, 10}, 0.5);
  const k::BlobParams p{};
  const auto stripe = [&](int a, int b) { return k::label_stripe(src, p, cv::Mat(), {a, b}); };
  using V = std::vector<k::BlobStripe>;
  EXPECT_THROW(k::merge_stripes(V{}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 3), stripe(4, 10)}, p), k::KernelError) << "gap";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 5), stripe(4, 10)}, p), k::KernelError) << "overlap";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 10), stripe(0, 10)}, p), k::KernelError) << "twice";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 10), stripe(9, 10)}, p), k::KernelError) << "last row twice";
  EXPECT_THROW(k::merge_stripes(V{stripe(5, 10), stripe(0, 5)}, p), k::KernelError) << "bottom to top";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 5)}, p), k::KernelError) << "bottom rows missing";
  EXPECT_THROW(k::merge_stripes(V{stripe(1, 10)}, p), k::KernelError) << "top row missing";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 9)}, p), k::KernelError) << "last row missing";
  EXPECT_THROW(k::merge_stripes(V{stripe(3, 3)}, p), k::KernelError) << "only an empty stripe";
  EXPECT_THROW(k::merge_stripes(V{stripe(0, 4), stripe(6, 6), stripe(7, 10)}, p), k::KernelError)
      << "gap next to an empty stripe";
  // Empty stripes anywhere are fine.
  EXPECT_NO_THROW(k::merge_stripes(V{stripe(0, 0), stripe(0, 4), stripe(4, 4), stripe(4, 10), stripe(10, 10)}, p));
  EXPECT_NO_THROW(k::merge_stripes(V{stripe(0, 4), stripe(20, 30), stripe(4, 10)}, p));  // clamped to [10, 10)
}

TEST(BlobStripes, MergeRefusesStripesOfOtherFramesOrParameters) {
  cv::RNG rng(kSeed + 23);
  const cv::Mat src = random_binary(rng, {16, 10}, 0.5);
  const cv::Mat wider = random_binary(rng, {17, 10}, 0.5);
  const cv::Mat taller = random_binary(rng, {16, 12}, 0.5);
  const k::BlobParams p{0, k::Connectivity::eight};
  const k::BlobParams four{0, k::Connectivity::four};
  const k::BlobParams t1{1, k::Connectivity::eight};
  using V = std::vector<k::BlobStripe>;
  const auto top = k::label_stripe(src, p, cv::Mat(), {0, 5});
  const auto bottom = k::label_stripe(src, p, cv::Mat(), {5, 10});
  EXPECT_NO_THROW(k::merge_stripes(V{top, bottom}, p));
  // Frames of other sizes, even in an empty stripe.
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(wider, p, cv::Mat(), {5, 10})}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(taller, p, cv::Mat(), {5, 10})}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{k::label_stripe(taller, p, cv::Mat(), {0, 5}), bottom}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(wider, p, cv::Mat(), {5, 5}), bottom}, p), k::KernelError);
  // Stripes labelled with other parameters than each other or than merge_stripes is given.
  EXPECT_THROW(k::merge_stripes(V{top, bottom}, four), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, bottom}, t1), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(src, four, cv::Mat(), {5, 10})}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(src, four, cv::Mat(), {5, 10})}, four), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(src, t1, cv::Mat(), {5, 10})}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::label_stripe(src, t1, cv::Mat(), {5, 5}), bottom}, p), k::KernelError);
  // Default-constructed stripes, alone or with good ones.
  EXPECT_THROW(k::merge_stripes(V{k::BlobStripe()}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{k::BlobStripe(), top, bottom}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, k::BlobStripe(), bottom}, p), k::KernelError);
  EXPECT_THROW(k::merge_stripes(V{top, bottom, k::BlobStripe()}, p), k::KernelError);
}

TEST(BlobStripes, LabelStripeRejectsInvalidArguments) {
  const cv::Mat src(6, 7, CV_8UC1, cv::Scalar(1));
  const cv::Range r(0, 3);
  EXPECT_THROW(k::label_stripe(cv::Mat(6, 7, CV_16SC1), {}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(cv::Mat(6, 7, CV_8UC3), {}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(cv::Mat(), {}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {-2, k::Connectivity::eight}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {256, k::Connectivity::eight}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {0, static_cast<k::Connectivity>(6)}, cv::Mat(), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {}, cv::Mat(6, 8, CV_8UC1), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {}, cv::Mat(7, 7, CV_8UC1), r), k::KernelError);
  EXPECT_THROW(k::label_stripe(src, {}, cv::Mat(6, 7, CV_16UC1), r), k::KernelError);
  // Checked even when the stripe is empty.
  EXPECT_THROW(k::label_stripe(src, {}, cv::Mat(7, 7, CV_8UC1), cv::Range(2, 2)), k::KernelError);
  EXPECT_NO_THROW(k::label_stripe(src, {-1, k::Connectivity::four}, cv::Mat(), r));
  EXPECT_NO_THROW(k::label_stripe(src, {255, k::Connectivity::four}, cv::Mat(), r));
}

}  // namespace
