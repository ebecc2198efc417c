// Tests of reading on a thread of its own: io::PrefetchingSource and run_stream built on it.
//
// PrefetchingSource: frames come out in order; the inner source's error comes after every frame
// read before it, once; stop() and the destructor end a reader blocked on a full queue; the stop
// flag ends reading; paced reading accounts for every frame (taken or dropped), a full queue keeps
// the newest frame and counts the ones it replaced, and the lag is at least what a late start or a
// slow source makes it and at most the time since the start.
//
// run_stream: over a generated MJPG video and over a scripted source, results equal run_frames'
// bit for bit, in order, for several thread counts and read-ahead depths; a slow source loses
// nothing; a source that fails after N frames gets those N delivered, then its error; a sink, a
// node or a bad frame that throws ends the run with that error, without a hang, and the reader is
// gone when run_stream returns (an endless source would otherwise be read on); the stop flag ends an
// endless stream; reading never runs further ahead of delivery than the queue and the frames in
// flight allow; real-time mode counts every frame of a finite source as processed or dropped, even
// with a sink slow enough that frames are dropped while waiting to be handed over, drops all but a
// few frames while the sink is blocked, and reports the lag of a source slower than the pace.
//
// Nothing is timed: slow parts sleep, but every expectation holds whatever the machine's speed.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/io/prefetching_source.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/node.hpp"
#include "pipeline/run_stats.hpp"
#include "pipeline/stream_runner.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)
namespace io = neopipe::pipeline::io;

namespace {

// Frame i of a scripted stream: noise and a few bright discs, all from seed i, so every frame
// differs and has blobs. Pixel (0, 0) holds i % 256 for tests that need to recognise a frame.
cv::Mat scripted_frame(std::int64_t i, cv::Size size, int type) {
  cv::RNG rng(static_cast<std::uint64_t>(1000 + i));
  cv::Mat f(size, type);
  rng.fill(f, cv::RNG::UNIFORM, 10, 70);
  for (int d = 0; d < 5; ++d) {
    cv::circle(f, {rng.uniform(0, size.width), rng.uniform(0, size.height)}, rng.uniform(2, 8),
               cv::Scalar::all(rng.uniform(150, 256)), cv::FILLED);
  }
  if (type == CV_8UC1) {
    f.at<std::uint8_t>(0, 0) = static_cast<std::uint8_t>(i % 256);
  } else {
    f.at<cv::Vec3b>(0, 0) = cv::Vec3b::all(static_cast<std::uint8_t>(i % 256));
  }
  return f;
}

struct Script {
  std::int64_t frames = 12;            ///< frames before the end (ignored when endless)
  bool endless = false;                ///< never ends
  std::int64_t fail_at = -1;           ///< throws SourceError instead of returning this frame
  std::int64_t odd_size_at = -1;       ///< this frame has another size (the executor rejects it)
  std::chrono::microseconds delay{0};  ///< sleeps this long in every next()
  cv::Size size{64, 48};
  int type = CV_8UC3;
};

// A FrameSource that plays a script, counting the calls it gets and noting calls that come after
// the test said it must not be read any more.
class ScriptedSource final : public io::FrameSource {
 public:
  explicit ScriptedSource(Script script) : script_(script) {}

  std::optional<io::SourceFrame> next() override {
    const std::int64_t i = calls_++;
    if (closed_) ++calls_after_close_;
    if (script_.delay.count() > 0) std::this_thread::sleep_for(script_.delay);
    if (i == script_.fail_at) throw io::SourceError("scripted: frame " + std::to_string(i) + " is unreadable");
    if (!script_.endless && i >= script_.frames) return std::nullopt;
    const cv::Size size =
        i == script_.odd_size_at ? cv::Size(script_.size.width + 2, script_.size.height) : script_.size;
    return io::SourceFrame{i, scripted_frame(i, size, script_.type)};
  }
  std::string description() const override { return "scripted"; }
  double fps() const override { return 0; }
  std::optional<std::int64_t> frame_count() const override {
    return script_.endless ? std::nullopt : std::optional<std::int64_t>(script_.frames);
  }

  std::int64_t calls() const { return calls_; }
  /// From now on, any call is an error (the reader should be gone).
  void close() { closed_ = true; }
  std::int64_t calls_after_close() const { return calls_after_close_; }

 private:
  Script script_;
  std::atomic<std::int64_t> calls_{0};
  std::atomic<bool> closed_{false};
  std::atomic<std::int64_t> calls_after_close_{0};
};

std::vector<cv::Mat> scripted_frames(const Script& s) {
  std::vector<cv::Mat> frames;
  for (std::int64_t i = 0; i < s.frames; ++i) frames.push_back(scripted_frame(i, s.size, s.type));
  return frames;
}

pl::CompiledGraph blob_graph() {
  return pl::compile(pl::blob_graph(), pl::standard_kernels());
}

// Runs `source` and keeps every result; rethrows what run_stream throws.
std::vector<pl::FrameResult> collect(io::FrameSource& source, pl::CompiledGraph graph, const pl::StreamOptions& options,
                                     pl::RunStats& stats) {
  std::vector<pl::FrameResult> results;
  pl::run_stream(
      source, std::move(graph), options, [&](const pl::FrameResult& r) { results.push_back(r); }, stats);
  return results;
}

void expect_same_results(const std::vector<pl::FrameResult>& got, const std::vector<pl::FrameResult>& want,
                         const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < got.size(); ++i) {
    const std::string frame = what + ", frame " + std::to_string(i);
    EXPECT_EQ(got[i].index, static_cast<std::int64_t>(i)) << frame;
    EXPECT_TRUE(same_image(got[i].input, want[i].input)) << frame;
    ASSERT_EQ(got[i].outputs.size(), want[i].outputs.size()) << frame;
    for (size_t k = 0; k < got[i].outputs.size(); ++k) {
      expect_same_value(got[i].outputs[k], want[i].outputs[k], frame + ", output " + std::to_string(k));
    }
  }
}

std::vector<std::int64_t> iota(std::int64_t n) {
  std::vector<std::int64_t> v;
  for (std::int64_t i = 0; i < n; ++i) v.push_back(i);
  return v;
}

// Copies its gray input; throws on the frame whose pixel (0, 0) is `fail_on`.
class FailOnMarkNode final : public pl::Node {
 public:
  explicit FailOnMarkNode(int fail_on)
      : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, neopipe::kernels::Footprint::frame),
        fail_on_(fail_on) {}
  void begin_frame(pl::NodeIO& io) override {
    if (io.image(0).at<std::uint8_t>(0, 0) == fail_on_) throw std::runtime_error("marked frame");
    io.image(0).copyTo(io.out_image(0));
  }

 private:
  int fail_on_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// PrefetchingSource

TEST(PrefetchingSource, GivesEveryFrameInOrderThenTheEnd) {
  for (const int capacity : {1, 2, 5}) {
    ScriptedSource inner({.frames = 9});
    io::PrefetchingSource source(inner, {.capacity = capacity});
    EXPECT_EQ(source.description(), "scripted");
    EXPECT_EQ(source.frame_count(), std::optional<std::int64_t>(9));
    for (std::int64_t i = 0; i < 9; ++i) {
      const auto f = source.next();
      ASSERT_TRUE(f.has_value()) << "capacity " << capacity << ", frame " << i;
      EXPECT_EQ(f->index, i);
      EXPECT_TRUE(same_image(f->image, scripted_frame(i, {64, 48}, CV_8UC3)));
    }
    EXPECT_FALSE(source.next().has_value());
    EXPECT_FALSE(source.next().has_value());  // and stays ended
    EXPECT_FALSE(source.interrupted());
  }
}

TEST(PrefetchingSource, ErrorComesAfterTheFramesReadBeforeIt) {
  ScriptedSource inner({.frames = 10, .fail_at = 4});
  io::PrefetchingSource source(inner, {.capacity = 3});
  std::vector<std::int64_t> got;
  try {
    while (auto f = source.next()) got.push_back(f->index);
    ADD_FAILURE() << "the error was lost";
  } catch (const io::SourceError& e) {
    EXPECT_EQ(std::string(e.what()), "scripted: frame 4 is unreadable");
  }
  EXPECT_EQ(got, iota(4));
  EXPECT_FALSE(source.next().has_value());  // reported once; reading does not resume after it
  EXPECT_EQ(inner.calls(), 5);
}

TEST(PrefetchingSource, StopEndsAReaderWaitingForRoom) {
  ScriptedSource inner({.endless = true});
  {
    io::PrefetchingSource source(inner, {.capacity = 1});
    const auto first = source.next();  // the reader has started; it soon blocks on the full queue
    ASSERT_TRUE(first.has_value());
    source.stop();  // returns: the reader woke up and ended
    inner.close();
    EXPECT_TRUE(source.interrupted());
    // What was queued can still be taken, then the stream ends.
    while (source.next()) {
    }
  }
  EXPECT_EQ(inner.calls_after_close(), 0);

  ScriptedSource again({.endless = true});
  {
    io::PrefetchingSource source(again, {.capacity = 2});
    ASSERT_TRUE(source.next().has_value());
  }  // the destructor stops and joins the reader
  again.close();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // room for a stray reader to show itself
  EXPECT_EQ(again.calls_after_close(), 0);
}

TEST(PrefetchingSource, StopFlagEndsReading) {
  ScriptedSource inner({.endless = true});
  std::atomic<bool> stop{false};
  io::PrefetchingSource source(inner, {.capacity = 2, .stop = &stop});
  std::int64_t taken = 0;
  while (auto f = source.next()) {
    EXPECT_EQ(f->index, taken);
    if (++taken == 5) stop = true;
  }
  EXPECT_TRUE(source.interrupted());
  EXPECT_GE(taken, 5);
  EXPECT_LE(taken, 5 + 2 + 1);  // what was queued or being read when the flag was set

  ScriptedSource untouched({.endless = true});
  const std::atomic<bool> stopped{true};
  io::PrefetchingSource none(untouched, {.stop = &stopped});
  EXPECT_FALSE(none.next().has_value());
  EXPECT_EQ(untouched.calls(), 0);
}

TEST(PrefetchingSource, PacedReadingAccountsForEveryFrame) {
  // 2000 frames/s into a one-frame queue, taken slowly: most frames are replaced while they wait.
  ScriptedSource inner({.frames = 40});
  io::PrefetchingSource source(inner, {.capacity = 1, .pace = 2000});
  std::vector<std::int64_t> got;
  while (auto f = source.next()) {
    got.push_back(f->index);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_EQ(static_cast<std::int64_t>(got.size()) + source.dropped(), 40);
  for (size_t i = 1; i < got.size(); ++i) EXPECT_LT(got[i - 1], got[i]);
}

TEST(PrefetchingSource, PacedReadingIntoAFullQueueKeepsTheNewestFrame) {
  // Every frame is due already (the clock started 10 s ago) and nothing is taken until the source is
  // exhausted: each frame read finds the one-frame queue full and replaces the frame in it, so 39
  // are dropped and the last one is left, whatever the machine's speed. Each read also began at
  // least 10 s - 39 / 2000 s after its due time, and no later than now.
  ScriptedSource inner({.frames = 40});
  const auto start = io::PrefetchingSource::Clock::now() - std::chrono::seconds(10);
  io::PrefetchingSource source(inner, {.capacity = 1, .pace = 2000}, start);
  for (int waited_ms = 0; inner.calls() <= 40 && waited_ms < 20000; ++waited_ms) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the reader's 41st call finds the end
  }
  std::vector<std::int64_t> got;
  while (auto f = source.next()) got.push_back(f->index);
  const double since_start = std::chrono::duration<double>(io::PrefetchingSource::Clock::now() - start).count();
  EXPECT_EQ(got, std::vector<std::int64_t>{39});
  EXPECT_EQ(source.dropped(), 39);
  EXPECT_GE(source.max_lag_s(), 10 - 39.0 / 2000);
  EXPECT_LE(source.max_lag_s(), since_start);

  // The same, with room for every frame: nothing is dropped, however late the reading.
  ScriptedSource roomy({.frames = 40});
  io::PrefetchingSource deep(roomy, {.capacity = 40, .pace = 2000}, start);
  got.clear();
  while (auto f = deep.next()) got.push_back(f->index);
  EXPECT_EQ(got, iota(40));
  EXPECT_EQ(deep.dropped(), 0);
}

TEST(PrefetchingSource, LagMeasuresASourceSlowerThanThePace) {
  // Frames due every 10 ms from a source that takes at least 20 ms a frame, so the reader never
  // waits: read k ends no earlier than 20 (k + 1) ms after the start, when its frame was due at
  // 10 k ms. Over 10 frames the lag of the last is at least 110 ms, on any machine. And as every read
  // takes longer than a period, no read's lag exceeds the last read's end less 90 ms, the last
  // frame's due time: a lag counted from the start of the stream instead of each frame's due time
  // would.
  ScriptedSource inner({.frames = 10, .delay = std::chrono::milliseconds(20)});
  const auto start = io::PrefetchingSource::Clock::now();
  io::PrefetchingSource source(inner, {.capacity = 10, .pace = 100}, start);
  std::int64_t taken = 0;
  while (source.next()) ++taken;
  const double since_start = std::chrono::duration<double>(io::PrefetchingSource::Clock::now() - start).count();
  EXPECT_EQ(taken, 10);
  EXPECT_EQ(source.dropped(), 0);
  EXPECT_GE(source.max_lag_s(), 0.110);
  EXPECT_LE(source.max_lag_s(), since_start - 0.090);
}

TEST(PrefetchingSource, RejectsAnEmptyQueue) {
  ScriptedSource inner({});
  EXPECT_THROW(io::PrefetchingSource(inner, {.capacity = 0}), std::invalid_argument);
  EXPECT_EQ(inner.calls(), 0);
}

// ---------------------------------------------------------------------------------------------
// run_stream

TEST(StreamRunner, VideoResultsEqualTheExecutorsInOrder) {
  const TempDir dir("neopipe_stream_runner_video");
  const std::string path = dir.file("clip.avi");
  const Script script{.frames = 24, .size = {96, 64}};
  {
    cv::VideoWriter w(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, script.size, true);
    ASSERT_TRUE(w.isOpened()) << "OpenCV cannot write MJPG through FFmpeg here";
    for (const auto& f : scripted_frames(script)) w.write(f);
  }
  // The reference: the decoded frames, read on this thread, through the executor alone.
  std::vector<cv::Mat> decoded;
  {
    const auto source = io::open_frame_source({path}, io::ColorFormat::bgr);
    while (auto f = source->next()) decoded.push_back(f->image);
  }
  ASSERT_EQ(decoded.size(), 24U);
  const auto want = pl::run_frames(blob_graph(), decoded, {.threads = 1});

  for (const int threads : {1, 2}) {
    for (const int read_ahead : {1, 3}) {
      const std::string what = std::to_string(threads) + " threads, read-ahead " + std::to_string(read_ahead);
      const auto source = io::open_frame_source({path}, io::ColorFormat::bgr);
      pl::StreamOptions options;
      options.executor = {.threads = threads, .frames_in_flight = 3};
      options.read_ahead = read_ahead;
      pl::RunStats stats;
      const auto got = collect(*source, blob_graph(), options, stats);
      expect_same_results(got, want, what);
      EXPECT_EQ(stats.frames_read, 24) << what;
      EXPECT_EQ(stats.frames_processed, 24) << what;
      EXPECT_FALSE(stats.interrupted) << what;
      EXPECT_FALSE(source->next().has_value()) << what;  // the source is the caller's again, at its end
    }
  }
}

TEST(StreamRunner, ScriptedResultsEqualTheExecutorsInOrder) {
  const Script script{.frames = 30};
  const auto want = pl::run_frames(blob_graph(), scripted_frames(script), {.threads = 1});
  for (const int read_ahead : {1, 2, 8}) {
    ScriptedSource source(script);
    pl::StreamOptions options;
    options.executor = {.threads = 2, .frames_in_flight = 4};
    options.read_ahead = read_ahead;
    pl::RunStats stats;
    expect_same_results(collect(source, blob_graph(), options, stats), want,
                        "read-ahead " + std::to_string(read_ahead));
    EXPECT_EQ(stats.frames_read, 30);
    EXPECT_EQ(stats.latency.count(), 30);
  }
}

TEST(StreamRunner, SlowSourceLosesNothing) {
  const Script script{.frames = 15, .delay = std::chrono::milliseconds(3)};
  const auto want = pl::run_frames(blob_graph(), scripted_frames(script), {.threads = 1});
  ScriptedSource source(script);
  pl::StreamOptions options;
  options.executor = {.threads = 2};
  std::vector<std::int64_t> progress;
  options.progress = [&](const pl::RunStats& s) { progress.push_back(s.frames_processed); };
  pl::RunStats stats;
  expect_same_results(collect(source, blob_graph(), options, stats), want, "slow source");
  EXPECT_EQ(progress, (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}));
  EXPECT_FALSE(stats.interrupted);
}

TEST(StreamRunner, SourceErrorComesAfterTheFramesBeforeIt) {
  for (const int read_ahead : {1, 4}) {
    for (const auto delay : {std::chrono::microseconds(0), std::chrono::microseconds(2000)}) {
      const std::string what =
          "read-ahead " + std::to_string(read_ahead) + ", delay " + std::to_string(delay.count()) + " us";
      ScriptedSource source({.frames = 20, .fail_at = 7, .delay = delay});
      pl::StreamOptions options;
      options.executor = {.threads = 2, .frames_in_flight = 3};
      options.read_ahead = read_ahead;
      pl::RunStats stats;
      std::vector<std::int64_t> delivered;
      try {
        pl::run_stream(
            source, blob_graph(), options, [&](const pl::FrameResult& r) { delivered.push_back(r.index); }, stats);
        ADD_FAILURE() << what << ": the error was lost";
      } catch (const io::SourceError& e) {
        EXPECT_EQ(std::string(e.what()), "scripted: frame 7 is unreadable") << what;
      }
      EXPECT_EQ(delivered, iota(7)) << what;
      EXPECT_EQ(stats.frames_read, 7) << what;
      EXPECT_EQ(stats.frames_processed, 7) << what;
      EXPECT_EQ(source.calls(), 8) << what;  // nothing read after the error
    }
  }
}

TEST(StreamRunner, SinkErrorEndsAnEndlessStreamAndTheReader) {
  for (const int read_ahead : {1, 3}) {
    ScriptedSource source({.endless = true});
    pl::StreamOptions options;
    options.executor = {.threads = 2, .frames_in_flight = 4};
    options.read_ahead = read_ahead;
    pl::RunStats stats;
    std::vector<std::int64_t> delivered;
    try {
      pl::run_stream(
          source, blob_graph(), options,
          [&](const pl::FrameResult& r) {
            delivered.push_back(r.index);
            if (r.index == 5) throw std::runtime_error("disk full");
          },
          stats);
      ADD_FAILURE() << "the sink's error was lost";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "disk full");
    }
    source.close();
    EXPECT_EQ(delivered, iota(6)) << "read-ahead " << read_ahead;  // and nothing after the failure
    std::this_thread::sleep_for(std::chrono::milliseconds(20));    // room for a stray reader to show itself
    EXPECT_EQ(source.calls_after_close(), 0) << "read-ahead " << read_ahead;
  }
}

TEST(StreamRunner, ProcessingErrorEndsAnEndlessStreamAndTheReader) {
  pl::KernelRegistry registry = pl::standard_kernels();
  registry.add({"fail_on_mark", "copies; throws on the frame whose pixel (0, 0) is 6",
                [](pl::NodeContext&) { return std::make_unique<FailOnMarkNode>(6); }});
  const auto graph = [&] {
    return pl::compile(pl::parse_graph_spec("nodes:\n"
                                            "  - {name: src, kernel: source, params: {format: gray}}\n"
                                            "  - {name: fail, kernel: fail_on_mark, inputs: {in: src}}\n"
                                            "outputs: fail\n",
                                            "fail.yaml"),
                       registry);
  };
  ScriptedSource source({.endless = true, .type = CV_8UC1});
  pl::StreamOptions options;
  options.executor = {.threads = 2, .frames_in_flight = 3};
  pl::RunStats stats;
  std::vector<std::int64_t> delivered;
  try {
    pl::run_stream(
        source, graph(), options, [&](const pl::FrameResult& r) { delivered.push_back(r.index); }, stats);
    ADD_FAILURE() << "the node's error was lost";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("marked frame"), std::string::npos) << e.what();
  }
  source.close();
  EXPECT_EQ(delivered, iota(6));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(source.calls_after_close(), 0);

  // A frame the executor rejects (another size) ends the run the same way, after the frames before it.
  ScriptedSource odd({.endless = true, .odd_size_at = 9});
  delivered.clear();
  pl::RunStats odd_stats;
  EXPECT_THROW(
      pl::run_stream(
          odd, blob_graph(), options, [&](const pl::FrameResult& r) { delivered.push_back(r.index); }, odd_stats),
      std::invalid_argument);
  odd.close();
  EXPECT_EQ(delivered, iota(9));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(odd.calls_after_close(), 0);
}

TEST(StreamRunner, StopFlagEndsAnEndlessStream) {
  for (const auto delay : {std::chrono::microseconds(0), std::chrono::microseconds(1000)}) {
    ScriptedSource source({.endless = true, .delay = delay});
    std::atomic<bool> stop{false};
    pl::StreamOptions options;
    options.executor = {.threads = 2, .frames_in_flight = 3};
    options.read_ahead = 3;
    options.stop = &stop;
    options.progress = [&](const pl::RunStats& s) {
      if (s.frames_processed == 10) stop = true;
    };
    pl::RunStats stats;
    std::vector<std::int64_t> delivered;
    pl::run_stream(
        source, blob_graph(), options, [&](const pl::FrameResult& r) { delivered.push_back(r.index); }, stats);
    source.close();
    EXPECT_TRUE(stats.interrupted);
    EXPECT_GE(stats.frames_processed, 10);
    EXPECT_EQ(stats.frames_processed, stats.frames_read);  // frames in flight finished; queued ones were not taken
    EXPECT_EQ(delivered, iota(stats.frames_processed));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(source.calls_after_close(), 0);
  }
}

TEST(StreamRunner, ReadingStaysBoundedAheadOfDelivery) {
  // A fast source and a slow sink: the reader runs as far ahead as it may, and no further.
  const int frames_in_flight = 3;
  const int read_ahead = 2;
  ScriptedSource source({.frames = 60});
  pl::StreamOptions options;
  options.executor = {.threads = 2, .frames_in_flight = frames_in_flight};
  options.read_ahead = read_ahead;
  pl::RunStats stats;
  std::int64_t worst = 0;
  pl::run_stream(
      source, blob_graph(), options,
      [&](const pl::FrameResult& r) {
        // Frames read but not delivered: in flight, taken by the driver, queued, or in the reader's hands.
        worst = std::max(worst, source.calls() - r.index);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      },
      stats);
  EXPECT_EQ(stats.frames_processed, 60);
  EXPECT_LE(worst, frames_in_flight + read_ahead + 3);
}

TEST(StreamRunner, RejectsNoReadAhead) {
  ScriptedSource source({});
  pl::StreamOptions options;
  options.read_ahead = 0;
  pl::RunStats stats;
  EXPECT_THROW(pl::run_stream(
                   source, blob_graph(), options, [](const pl::FrameResult&) {}, stats),
               std::invalid_argument);
  EXPECT_EQ(source.calls(), 0);
}

namespace {

// Runs `source` through the blob graph paced at `fps` on 2 threads with `frames_in_flight` frames
// at once, `sink` taking each result.
pl::RunStats run_paced(ScriptedSource& source, double fps, int frames_in_flight,
                       const std::function<void(const pl::FrameResult&)>& sink) {
  pl::StreamOptions options;
  options.realtime = true;
  options.fps = fps;
  options.executor = {.threads = 2, .frames_in_flight = frames_in_flight};
  pl::RunStats stats;
  pl::run_stream(source, blob_graph(), options, sink, stats);
  return stats;
}

}  // namespace

TEST(StreamRunner, RealtimeCountsEveryFrameAsProcessedOrDropped) {
  // A sink slower than the pace: frames are dropped, at the pipeline or while waiting to be handed
  // over, and every one of them is counted.
  for (const int sink_ms : {0, 4}) {
    ScriptedSource source({.frames = 50});
    std::vector<std::int64_t> delivered;
    const pl::RunStats stats = run_paced(source, 1000, 2, [&](const pl::FrameResult& r) {
      delivered.push_back(r.index);
      std::this_thread::sleep_for(std::chrono::milliseconds(sink_ms));
    });
    EXPECT_TRUE(stats.realtime);
    EXPECT_EQ(stats.frames_read, 50) << "sink " << sink_ms << " ms";
    EXPECT_EQ(stats.frames_processed + stats.frames_dropped, 50) << "sink " << sink_ms << " ms";
    EXPECT_EQ(static_cast<std::int64_t>(delivered.size()), stats.frames_processed);
    for (size_t i = 1; i < delivered.size(); ++i) EXPECT_LT(delivered[i - 1], delivered[i]);
    // A read cannot lag its due time by more than the run has lasted.
    EXPECT_GE(stats.max_reader_lag_s, 0);
    EXPECT_LE(stats.max_reader_lag_s, stats.seconds);
  }
}

TEST(StreamRunner, RealtimeDropsFramesWhileTheSinkIsBlocked) {
  // The sink blocks on the first frame it gets until the reader has read the whole source (50 frames
  // at 1000/s), so the driver, which delivers, takes nothing meanwhile. By then at most
  // frames_in_flight + 1 frames have entered the pipeline or are in the driver's hands (a slot
  // frees when the first frame completes, before its delivery, and a submit delivers before it
  // admits); once the sink returns, the reader has ended with at most the newest frame waiting. So
  // at most frames_in_flight + 2 frames are processed and the other 46 or more are dropped, however
  // fast or slow the machine. (The first frame delivered need not be frame 0: on a slow start
  // frame 1 may already have replaced it.)
  const std::int64_t frames = 50;
  const int frames_in_flight = 2;
  ScriptedSource source({.frames = frames});
  std::vector<std::int64_t> delivered;
  const pl::RunStats stats = run_paced(source, 1000, frames_in_flight, [&](const pl::FrameResult& r) {
    delivered.push_back(r.index);
    if (delivered.size() != 1) return;
    // The reader's call after the last frame finds the end. (The cap only keeps a broken reader
    // from hanging the test; the expectations below do not depend on it.)
    for (int waited_ms = 0; source.calls() <= frames && waited_ms < 20000; ++waited_ms) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  EXPECT_EQ(source.calls(), frames + 1);
  EXPECT_EQ(stats.frames_read, frames);
  EXPECT_EQ(stats.frames_processed + stats.frames_dropped, frames);
  EXPECT_GE(stats.frames_processed, 1);
  EXPECT_LE(stats.frames_processed, frames_in_flight + 2);
  EXPECT_GE(stats.frames_dropped, frames - frames_in_flight - 2);
  EXPECT_EQ(static_cast<std::int64_t>(delivered.size()), stats.frames_processed);
  for (size_t i = 1; i < delivered.size(); ++i) EXPECT_LT(delivered[i - 1], delivered[i]);
}

TEST(StreamRunner, RealtimeReportsHowFarASlowSourceFallsBehind) {
  // A source that takes at least 20 ms a frame, paced at 100 frames/s: read k ends at least
  // 20 (k + 1) ms after the start, its frame due at 10 k ms, so over 10 frames the reader falls at
  // least 110 ms behind, on any machine; and by no more than the run lasted less the last frame's due
  // time, 90 ms (PrefetchingSource.LagMeasuresASourceSlowerThanThePace says why).
  ScriptedSource source({.frames = 10, .delay = std::chrono::milliseconds(20)});
  const pl::RunStats stats = run_paced(source, 100, 4, [](const pl::FrameResult&) {});
  EXPECT_EQ(stats.frames_read, 10);
  EXPECT_EQ(stats.frames_processed + stats.frames_dropped, 10);
  EXPECT_GE(stats.max_reader_lag_s, 0.110);
  EXPECT_LE(stats.max_reader_lag_s, stats.seconds - 0.090);
}
