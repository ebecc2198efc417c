#pragma once
// The stopwatch and the statistic every timed peer in neopipe bench shares.

#include <algorithm>
#include <chrono>
#include <vector>

namespace neopipe::bench {

inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The upper median: robust to the one slow repeat a shared machine gives.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace neopipe::bench
