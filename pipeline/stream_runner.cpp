#include "pipeline/stream_runner.hpp"

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

#include "pipeline/io/prefetching_source.hpp"

namespace neopipe::pipeline {
namespace {
using Clock = std::chrono::steady_clock;

// How long the driver waits for the reader before delivering finished results anyway.
constexpr auto kPollInterval = std::chrono::milliseconds(2);

bool stopped(const StreamOptions& o) {
  return o.stop != nullptr && o.stop->load();
}

// Real-time mode: frames the reader dropped from its full queue were read, and dropped.
class ReaderDrops {
 public:
  void fold_into(const io::PrefetchingSource& reader, RunStats& stats) {
    const std::int64_t now = reader.dropped();
    stats.frames_read += now - seen_;
    stats.frames_dropped += now - seen_;
    seen_ = now;
    stats.max_reader_lag_s = reader.max_lag_s();
  }

 private:
  std::int64_t seen_ = 0;
};

// Takes frames from the reader and submits them, delivering results while it waits, until the
// stream ends or the stop flag is set. Batch mode blocks while the pipeline is full; real-time mode
// drops a frame that finds it full.
void drive(io::PrefetchingSource& reader, Executor& ex, const StreamOptions& o, RunStats& stats, ReaderDrops& drops) {
  for (;;) {
    if (stopped(o)) {
      stats.interrupted = true;
      return;
    }
    std::optional<io::SourceFrame> f;
    const bool ready = reader.next_within(kPollInterval, f);
    if (o.realtime) drops.fold_into(reader, stats);
    if (!ready) {
      ex.poll();
      continue;
    }
    if (!f) {
      if (reader.interrupted()) stats.interrupted = true;
      return;
    }
    ++stats.frames_read;
    if (!o.realtime) {
      ex.submit(f->index, f->image);
    } else if (!ex.try_submit(f->index, f->image)) {
      ++stats.frames_dropped;
    }
  }
}

}  // namespace

void run_stream(io::FrameSource& source, CompiledGraph graph, const StreamOptions& options,
                const std::function<void(const FrameResult&)>& sink, RunStats& stats) {
  if (options.read_ahead < 1) {
    throw std::invalid_argument("run_stream: read_ahead must be at least 1, not " + std::to_string(options.read_ahead));
  }
  const std::optional<size_t> blob_output = graph.find_output(PortType::blobs);
  io::PrefetchOptions prefetch;
  prefetch.capacity = options.realtime ? 1 : options.read_ahead;
  prefetch.stop = options.stop;
  if (options.realtime) {
    prefetch.pace = options.fps > 0 ? options.fps : (source.fps() > 0 ? source.fps() : 30.0);
    stats.realtime = true;
  }
  // Set once the executor is built: the pace (and the run's time) starts when the pipeline can take
  // a frame, so a slow start-up does not make the first frames late and drop them.
  Clock::time_point start;
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  Executor ex(std::move(graph), options.executor, [&](FrameResult&& r) {
    ++stats.frames_processed;
    stats.latency.add(r.latency_s);
    if (blob_output) stats.blobs += static_cast<std::int64_t>(std::get<BlobList>(r.outputs[*blob_output]).size());
    sink(r);
    stats.seconds = elapsed();
    if (options.progress) options.progress(stats);
  });
  start = Clock::now();
  std::optional<io::PrefetchingSource> reader;
  ReaderDrops drops;
  const auto stop_reader = [&] {
    if (!reader) return;
    reader->stop();
    if (options.realtime) drops.fold_into(*reader, stats);
  };
  try {
    reader.emplace(source, prefetch, start);
    drive(*reader, ex, options, stats, drops);
    stop_reader();  // frames it read ahead after a stop request are not processed
    ex.finish();
  } catch (...) {
    stop_reader();
    // Deliver whatever finished before the error. An error that comes up doing so belongs to an
    // earlier frame than a reading error (or is the same processing or sink error), so it is the
    // first error, the one to report.
    try {
      ex.finish();
    } catch (...) {
      stats.seconds = elapsed();
      throw;
    }
    stats.seconds = elapsed();
    throw;
  }
  stats.seconds = elapsed();
}

}  // namespace neopipe::pipeline
