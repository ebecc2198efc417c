#pragma once
// Drives a frame source through a graph: batch mode (every frame, in order) or real-time mode
// (paced to the source's frame rate, dropping frames that find the pipeline full).
//
// Real-time drop policy: frame i "arrives" at start + i / fps and is read then (or at once, if
// reading is already late). It enters the pipeline if one of its `frames_in_flight` slots is free,
// and is dropped otherwise: frames are never queued, so latency and memory stay bounded and the
// newest frames win. Drops measure processing falling behind; a source that decodes slower than its
// own frame rate is not dropped from but falls behind the clock, which RunStats::max_reader_lag_s
// reports.

#include <atomic>
#include <functional>
#include <optional>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/run_stats.hpp"

namespace neopipe::pipeline {

struct StreamOptions {
  ExecutorOptions executor;
  bool realtime = false;
  double fps = 0;                           ///< real-time pace; 0 = the source's rate, or 30 if it has none
  const std::atomic<bool>* stop = nullptr;  ///< when set, stop reading; frames in flight still finish
  /// Called on the driver thread after each delivered frame.
  std::function<void(const RunStats&)> progress;
};

/// Runs `source` through `graph`, passing each result to `sink` in frame order. `stats` is kept up
/// to date as frames finish, so it is meaningful even when this throws. The first error (reading,
/// processing or the sink's own) is rethrown after every frame processed before it was delivered.
void run_stream(io::FrameSource& source, CompiledGraph graph, const StreamOptions& options,
                const std::function<void(const FrameResult&)>& sink, RunStats& stats);

}  // namespace neopipe::pipeline
