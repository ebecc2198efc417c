#include "pipeline/stream_runner.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace neopipe::pipeline {
namespace {
using Clock = std::chrono::steady_clock;

bool stopped(const StreamOptions& o) {
  return o.stop != nullptr && o.stop->load();
}

void read_all(io::FrameSource& source, Executor& ex, const StreamOptions& o, RunStats& stats) {
  while (!stopped(o)) {
    auto f = source.next();
    if (!f) return;
    ++stats.frames_read;
    ex.submit(f->index, f->image);
  }
  stats.interrupted = true;
}

void read_paced(io::FrameSource& source, Executor& ex, const StreamOptions& o, RunStats& stats) {
  const double rate = o.fps > 0 ? o.fps : (source.fps() > 0 ? source.fps() : 30.0);
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  const auto start = Clock::now();
  stats.realtime = true;
  for (std::int64_t i = 0;; ++i) {
    if (stopped(o)) {
      stats.interrupted = true;
      return;
    }
    const auto due = start + i * period;
    while (Clock::now() < due) {
      ex.poll();
      std::this_thread::sleep_until(std::min(due, Clock::now() + std::chrono::milliseconds(2)));
    }
    auto f = source.next();
    if (!f) return;
    ++stats.frames_read;
    stats.max_reader_lag_s =
        std::max(stats.max_reader_lag_s, std::chrono::duration<double>(Clock::now() - due).count());
    if (!ex.try_submit(f->index, f->image)) ++stats.frames_dropped;
  }
}

}  // namespace

void run_stream(io::FrameSource& source, CompiledGraph graph, const StreamOptions& options,
                const std::function<void(const FrameResult&)>& sink, RunStats& stats) {
  const std::optional<size_t> blob_output = graph.find_output(PortType::blobs);
  const auto start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  Executor ex(std::move(graph), options.executor, [&](FrameResult&& r) {
    ++stats.frames_processed;
    stats.latency.add(r.latency_s);
    if (blob_output) stats.blobs += static_cast<std::int64_t>(std::get<BlobList>(r.outputs[*blob_output]).size());
    sink(r);
    stats.seconds = elapsed();
    if (options.progress) options.progress(stats);
  });
  try {
    if (options.realtime) {
      read_paced(source, ex, options, stats);
    } else {
      read_all(source, ex, options, stats);
    }
    ex.finish();
  } catch (...) {
    // Deliver whatever finished before the error; the first error is the one to report.
    try {
      ex.finish();
    } catch (...) {
    }
    stats.seconds = elapsed();
    throw;
  }
  stats.seconds = elapsed();
}

}  // namespace neopipe::pipeline
