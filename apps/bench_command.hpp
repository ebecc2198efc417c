#pragma once
// `neopipe bench`: neopipe graphs side by side with the same work as OpenCV calls and a memory-read
// floor, on generated frames; sweeps over frame size and blob count; thread scaling; peak memory;
// and a video's decode-only rate beside `neopipe run`'s.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace neopipe::apps {

struct BenchArgs {
  std::vector<std::string> sizes;  ///< "WxH"; empty: 256x256, 640x480, 1920x1080 (a sweep has its own)
  std::vector<int> threads;        ///< empty: 1 and all hardware threads
  bool scaling = false;            ///< every thread count from 1 to all hardware threads
  std::vector<std::string> cases;  ///< empty: dots dense chain (dots for a sweep; none with --video alone)
  std::string sweep;               ///< "", "size" or "blobs"
  std::string video;               ///< a video file to measure decode-only against `neopipe run`
  std::string graph;               ///< a user's graph spec (YAML) to time on the dots frames
  bool json = false;
  double min_seconds = 0.3;
  int repeats = 5;
};

CLI::App* add_bench_command(CLI::App& parent, BenchArgs& args);
int bench_command(const BenchArgs& args);

}  // namespace neopipe::apps
