#pragma once
// What a run reports: frames in, processed and dropped, blobs, throughput and per-frame latency.

#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/latency_histogram.hpp"

namespace neopipe::pipeline {

struct RunStats {
  std::int64_t frames_read = 0;       ///< frames taken from the source (processed + dropped)
  std::int64_t frames_processed = 0;  ///< frames whose results were delivered
  std::int64_t frames_dropped = 0;    ///< real-time mode only
  std::int64_t blobs = 0;
  double seconds = 0;        ///< wall time from the first read to the last result
  LatencyHistogram latency;  ///< per processed frame, submit to result, in seconds
  bool interrupted = false;
  bool realtime = false;        ///< paced to the source's frame rate
  double max_reader_lag_s = 0;  ///< real-time: how far reading fell behind the frames' arrival

  double frames_per_second() const { return seconds > 0 ? static_cast<double>(frames_processed) / seconds : 0; }
  /// The q-quantile (0..1) of the latencies, nearest rank, within 0.14 %; 0 with no frames.
  double latency_quantile(double q) const { return latency.quantile(q); }
  /// One line for people: "120 frames, 0 dropped, 1440 blobs in 0.41 s (292.7 frames/s); latency ...".
  std::string summary() const;
};

}  // namespace neopipe::pipeline
