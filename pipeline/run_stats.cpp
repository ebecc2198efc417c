#include "pipeline/run_stats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace neopipe::pipeline {

std::string RunStats::summary() const {
  std::string s =
      fmt::format("{} frames, {} dropped, {} blobs in {:.3f} s ({:.1f} frames/s); latency p50 {:.2f} ms, p99 {:.2f} ms",
                  frames_processed, frames_dropped, blobs, seconds, frames_per_second(), 1e3 * latency_quantile(0.5),
                  1e3 * latency_quantile(0.99));
  if (realtime) s += fmt::format("; reader lag max {:.1f} ms", 1e3 * max_reader_lag_s);
  if (interrupted) s += " (interrupted)";
  return s;
}

}  // namespace neopipe::pipeline
