#pragma once
// `neopipe bench`: the built-in blob graph side by side with OpenCV and a memory-read floor.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace neopipe::apps {

struct BenchArgs {
  std::vector<std::string> sizes;  ///< "WxH"; empty: 256x256, 640x480, 1920x1080
  int threads = 0;                 ///< 0: both 1 and all hardware threads
  std::vector<std::string> cases;  ///< empty: dots and dense
  bool json = false;
  double min_seconds = 0.3;
  int repeats = 3;
};

CLI::App* add_bench_command(CLI::App& parent, BenchArgs& args);
int bench_command(const BenchArgs& args);

}  // namespace neopipe::apps
