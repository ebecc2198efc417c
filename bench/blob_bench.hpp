#pragma once
// The side-by-side blob benchmark behind `neopipe bench`: neopipe's built-in blob graph, the OpenCV
// way and the memory-read floor, on the same generated frames, in the same run.

#include <functional>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

namespace neopipe::bench {

struct BenchCase {
  std::string name;  ///< "dots" or "dense"
  cv::Size size;
  int threads;
};

struct BenchRecord {
  std::string case_name;
  std::string impl;  ///< "neopipe", "opencv" or "floor"
  int width = 0;
  int height = 0;
  int threads = 0;
  double fps = 0;     ///< median over the repeats
  double mpix_s = 0;  ///< fps * width * height / 1e6
};

struct BenchOptions {
  double min_seconds = 0.3;  ///< each timed run lasts at least this long
  int repeats = 3;           ///< runs per measurement; the median is reported
  int distinct_frames = 8;   ///< different generated frames cycled through
};

/// Measures one case with all three implementations.
std::vector<BenchRecord> run_blob_bench(const BenchCase& c, const BenchOptions& o);

/// Checks that neopipe and OpenCV find the same number of blobs on the case's first frame (a
/// benchmark of two programs that disagree measures nothing); returns an explanation if not.
std::string cross_check(const BenchCase& c);

}  // namespace neopipe::bench
