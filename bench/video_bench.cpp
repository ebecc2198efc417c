#include "bench/video_bench.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>
#include <streambuf>
#include <variant>

#include "bench/timing.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/io/blob_table_writer.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/media/media.hpp"
#include "pipeline/stream_runner.hpp"

namespace neopipe::bench {
namespace {

namespace io = pipeline::io;
using Clock = std::chrono::steady_clock;

// Issue 3's reference for decode-only: the loop a user would write with OpenCV.
double time_opencv_decode(const std::string& path, double min_seconds) {
  // Opened once untimed: it loads OpenCV's videoio (the media plug-in), which no timed pass should pay for.
  if (!pipeline::media::open_video_reader(path)) throw io::SourceError(path + ": cv::VideoCapture cannot open it");
  std::int64_t frames = 0;
  double seconds = 0;
  while (seconds < min_seconds) {
    const auto t0 = Clock::now();
    const auto cap = pipeline::media::open_video_reader(path);
    if (!cap) throw io::SourceError(path + ": cv::VideoCapture cannot open it");
    const std::int64_t before = frames;
    bool out_of_time = false;
    cv::Mat frame;
    for (;;) {
      out_of_time = seconds + seconds_since(t0) >= min_seconds;
      if (out_of_time || !cap->read(frame)) break;
      ++frames;
    }
    seconds += seconds_since(t0);
    // A pass whose time ran out while the file was being opened reads nothing, and that is fine.
    if (frames == before && !out_of_time) throw io::SourceError(path + ": cv::VideoCapture decodes no frame of it");
  }
  return static_cast<double>(frames) / seconds;
}

double time_decode(const std::string& path, io::ColorFormat format, double min_seconds) {
  std::int64_t frames = 0;
  double seconds = 0;
  while (seconds < min_seconds) {
    const auto t0 = Clock::now();
    const auto source = io::open_frame_source({path}, format);
    while (seconds + seconds_since(t0) < min_seconds && source->next()) ++frames;
    seconds += seconds_since(t0);
  }
  return static_cast<double>(frames) / seconds;
}

// Takes every byte and keeps none: the table is formatted and written as `neopipe run` writes it,
// without a disk's speed in the measurement.
class DiscardingBuffer final : public std::streambuf {
 protected:
  std::streamsize xsputn(const char* /*s*/, std::streamsize n) override { return n; }
  int_type overflow(int_type c) override { return traits_type::not_eof(c); }
};

double time_run(const std::string& path, const pipeline::GraphSpec& graph, io::ColorFormat format, int threads,
                double min_seconds, bool write_table) {
  DiscardingBuffer discard;
  std::ostream sink(&discard);
  std::int64_t frames = 0;
  double seconds = 0;
  std::atomic<bool> stop{false};
  pipeline::StreamOptions so;
  so.executor.threads = threads;
  so.stop = &stop;
  while (seconds < min_seconds) {
    pipeline::CompiledGraph compiled = pipeline::compile(graph, pipeline::standard_kernels());
    const std::optional<size_t> blob_output = compiled.find_output(pipeline::PortType::blobs);  // as `run` finds it
    const auto t0 = Clock::now();
    const auto source = io::open_frame_source({path}, format);
    pipeline::RunStats stats;
    const double before = seconds;
    std::optional<io::BlobTableWriter> table;
    if (write_table) table.emplace(sink, io::TableOptions{});
    pipeline::run_stream(
        *source, std::move(compiled), so,
        [&](const pipeline::FrameResult& r) {
          if (table && blob_output) table->write(r.index, std::get<pipeline::BlobList>(r.outputs[*blob_output]));
          ++frames;
          if (before + seconds_since(t0) >= min_seconds) stop = true;
        },
        stats);
    seconds += seconds_since(t0);
  }
  return static_cast<double>(frames) / seconds;
}

}  // namespace

VideoInfo probe_video(const std::string& path, io::ColorFormat format) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw io::SourceError(path + ": a directory, not a video file");
  const auto source = io::open_frame_source({path}, format);  // names the file if missing or unreadable
  if (io::is_image_file(path)) throw io::SourceError(path + ": an image, not a video file");
  const auto first = source->next();
  if (!first) throw io::SourceError(path + ": the video has no frames");
  VideoInfo info;
  info.path = path;
  info.size = first->image.size();
  info.frames = source->frame_count();
  info.fps = source->fps();
  return info;
}

std::vector<VideoRecord> run_video_bench(const std::string& path, const pipeline::GraphSpec& graph,
                                         io::ColorFormat format, int threads, const BenchOptions& o) {
  std::vector<double> opencv_decode;
  std::vector<double> decode;
  std::vector<double> run;
  std::vector<double> run_csv;
  for (int r = 0; r < std::max(o.repeats, 1); ++r) {
    opencv_decode.push_back(time_opencv_decode(path, o.min_seconds));
    decode.push_back(time_decode(path, format, o.min_seconds));
    run.push_back(time_run(path, graph, format, threads, o.min_seconds, false));
    run_csv.push_back(time_run(path, graph, format, threads, o.min_seconds, true));
  }
  return {{"opencv_decode", threads, median(opencv_decode)},
          {"decode", threads, median(decode)},
          {"run", threads, median(run)},
          {"run_csv", threads, median(run_csv)}};
}

}  // namespace neopipe::bench
