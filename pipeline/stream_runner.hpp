#pragma once
// Drives a frame source through a graph: batch mode (every frame, in order) or real-time mode
// (paced to the source's frame rate, dropping frames that find the pipeline full).
//
// Threads: the source is read (a video decoded) on a reader thread of its own, into a small bounded
// queue; the calling thread (the driver) takes frames from it, submits them to the executor and
// delivers the results to the sink. So decoding frame t+1 overlaps with processing frame t and with
// writing frame t-1's results, and memory stays bounded whatever the length of the stream: the
// executor's frames in flight, the one the driver is submitting, and at most `read_ahead` frames
// read but not yet taken, the one being decoded included (real-time mode: one waiting to be taken
// and one being read).
//
// Batch mode: the reader waits while the queue is full, the driver while the pipeline is.
//
// Real-time drop policy: frame i "arrives" at start + i / fps and is read then (or at once, if
// reading is already late). It enters the pipeline if one of its `frames_in_flight` slots is free,
// and is dropped otherwise: frames are not queued beyond a one-frame hand-over to the driver (a
// frame still waiting there when the next arrives is dropped too), so latency and memory stay
// bounded and the newest frames win. Drops measure processing (and delivery) falling behind; a
// source that decodes slower than its own frame rate is not dropped from but falls behind the
// clock, which RunStats::max_reader_lag_s reports.
//
// RunStats::frames_read counts the frames taken from the source into the run (processed or
// dropped); frames read ahead but never taken, because of a stop request or an error, are not.

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
  /// Batch mode: frames the reader thread may have read ahead of the driver, the one it is decoding
  /// included (>= 1). Each costs a frame's memory (6 MB for 1080p BGR).
  int read_ahead = 2;
  /// Called on the driver thread after each delivered frame.
  std::function<void(const RunStats&)> progress;
};

/// Runs `source` through `graph`, passing each result to `sink` in frame order. `stats` is kept up
/// to date as frames finish, so it is meaningful even when this throws. The first error (reading,
/// processing or the sink's own) is rethrown after every frame processed before it was delivered;
/// the reader thread has ended by then, whatever happened, so `source` is the caller's again.
/// Throws std::invalid_argument if `read_ahead` is below 1.
void run_stream(io::FrameSource& source, CompiledGraph graph, const StreamOptions& options,
                const std::function<void(const FrameResult&)>& sink, RunStats& stats);

}  // namespace neopipe::pipeline
