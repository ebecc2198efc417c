#include "apps/run_command.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "calib/calibration.hpp"
#include "calib/plane_pose.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/io/annotator.hpp"
#include "pipeline/io/blob_table_writer.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/stream_runner.hpp"

namespace neopipe::apps {
namespace {

namespace pl = neopipe::pipeline;
namespace io = neopipe::pipeline::io;

// Ctrl-C (SIGINT) or SIGTERM asks the run to stop reading; frames in flight still finish and their
// rows are written. A signal handler can reach nothing but globals, so these are the program's.
std::atomic<bool> g_stop_requested{false};
std::atomic<int> g_stop_signal{0};
extern "C" void on_interrupt(int signal) {
  g_stop_signal.store(signal);
  g_stop_requested.store(true);
}

void list_kernels() {
  const pl::KernelRegistry registry = pl::standard_kernels();
  for (const auto* k : registry.all()) fmt::print("{:<10} {}\n", k->name, k->summary);
}

}  // namespace

pl::GraphSpec run_graph(const RunArgs& a) {
  if (!a.graph.empty()) {
    if (!a.threshold.empty() || a.connectivity != 0) {
      throw UsageError{"--threshold and --connectivity configure the built-in blob graph; with --graph, set them in " +
                       a.graph};
    }
    return pl::load_graph_spec(a.graph);
  }
  pl::BlobGraphOptions o;
  if (!a.threshold.empty() && a.threshold != "otsu") o.threshold = std::stoi(a.threshold);
  o.connectivity = a.connectivity == 0 ? 8 : a.connectivity;
  // Nothing but --annotate looks at colour, so the frames are read gray: from a video, that is the
  // decoder's luma plane, with no colour conversion at all. --annotate draws on the frames the graph
  // read and keeps their colour: it reads BGR and converts in the graph. That gray is BT.601 of
  // swscale's BGR, which truncates: on colourful video 1-2 levels darker than the luma on most
  // pixels (tests/pipeline/test_libav_video_source.cpp), so tables can differ slightly.
  o.source = a.annotate.empty() ? pl::PortType::gray8 : pl::PortType::bgr8;
  return pl::blob_graph(o);
}

io::ColorFormat run_source_format(const pl::CompiledGraph& graph) {
  return graph.source_type() == pl::PortType::bgr8 ? io::ColorFormat::bgr : io::ColorFormat::gray;
}

CLI::App* add_run_command(CLI::App& parent, RunArgs& a) {
  CLI::App* cmd = parent.add_subcommand("run", "Process a video or images through a graph; write the blob table");
  cmd->footer(
      "Without --graph: the built-in blob graph, gray (BT.601) -> threshold (Otsu per frame) -> blobs (8-connected).\n"
      "Frames are read gray (a video's luma plane), or in colour with --annotate, which draws on them.\n"
      "Blob table columns: frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy (with --moments also mu20,mu11,mu02).\n"
      "Exit status: 0 done, 1 bad input or failed processing (a full disk included), 2 bad command line, 130 "
      "interrupted (Ctrl-C), 143 terminated (SIGTERM); both after writing the rows of every frame read. A "
      "closed output pipe ends it as it ends any filter (killed by SIGPIPE, 141).");
  cmd->add_option("inputs", a.inputs, "A video file, or image files and directories of images")->type_name("INPUT...");
  cmd->add_option("--graph", a.graph, "Graph spec (YAML) to run instead of the built-in blob graph")
      ->check(CLI::ExistingFile)
      ->type_name("G.yaml");
  cmd->add_option("--threshold", a.threshold, "Built-in graph: fixed threshold T (foreground is value > T), or otsu")
      ->check(CLI::Range(0, 255) | CLI::IsMember({"otsu"}))
      ->type_name("T");
  cmd->add_option("--connectivity", a.connectivity, "Built-in graph: blob connectivity")
      ->check(CLI::IsMember({4, 8}))
      ->type_name("4|8");
  cmd->add_option("--out", a.out, "Write the blob table here (.csv or .jsonl) instead of stdout")
      ->type_name("FILE.csv|FILE.jsonl");
  cmd->add_option("--format", a.format, "Table format (default: from --out's extension, else csv)")
      ->check(CLI::IsMember({"csv", "jsonl"}));
  cmd->add_option("--annotate", a.annotate,
                  "Draw the blobs over the frames into a video (.mp4/.avi/.mkv) or images (.png/.jpg; one per frame)")
      ->type_name("OUT.mp4|OUT.png");
  cmd->add_flag("--realtime", a.realtime,
                "Pace to the source frame rate; a frame that finds the pipeline full is dropped and counted");
  cmd->add_option("--fps", a.fps, "Frame rate for --realtime (default: the video's; 30 for images)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", a.threads, "Worker threads (default: one per hardware thread)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--frames-in-flight", a.frames_in_flight, "Frames processed at once (default: 2 x (threads + 2))")
      ->check(CLI::Range(2, 256));
  cmd->add_flag("--moments", a.moments, "Add the second central moments mu20,mu11,mu02 to the table");
  cmd->add_option("--calib", a.calib,
                  "Calibration (neopipe calibrate): add X,Y, the weighted centroid on the workspace (mm)")
      ->type_name("calib.yaml");
  cmd->add_option("--height", a.height,
                  "With --calib: the blobs' centres lie this far above the calibrated plane, mm (a marble's centre: "
                  "its radius, less the calibration board's thickness); needs the full model")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", a.quiet, "No progress bar and no summary");
  cmd->add_flag("--list-kernels", a.list_kernels, "List the kernels a graph spec can use, and exit");
  return cmd;
}

int run_command(const RunArgs& a) {
  if (a.list_kernels) {
    list_kernels();
    return kExitOk;
  }
  if (a.inputs.empty()) throw UsageError{"no INPUT given (a video file, image files or a directory of images)"};
  if (a.height != 0 && a.calib.empty()) throw UsageError{"--height maps blobs through a calibration: give --calib"};
  if (!std::isfinite(a.height)) throw UsageError{fmt::format("--height {}: must be a number of mm", a.height)};

  pl::CompiledGraph graph = pl::compile(run_graph(a), pl::standard_kernels());
  const auto blob_output = graph.find_output(pl::PortType::blobs);
  if (!blob_output) {
    throw pl::GraphError({graph.origin(), 0, 0},
                         "the graph has no output of type blobs, so there is no blob table to write");
  }
  if (graph.source_type() == pl::PortType::s16) {
    // Files decode to 8-bit pixels; s16 frames (the panoramic sensor's ring) exist only in memory.
    throw pl::GraphError({graph.origin(), 0, 0},
                         "the graph's source takes s16 frames, which image and video files do not hold (use "
                         "format gray or bgr)");
  }
  const auto source = io::open_frame_source(a.inputs, run_source_format(graph));

  io::TableOptions table;
  table.moments = a.moments;
  std::optional<calib::Calibration> calibration;
  if (!a.calib.empty()) {
    calibration = calib::load_calibration(a.calib);
    if (a.height != 0) (void)calib::plane_pose(*calibration);  // refuses the plane homography now, not per frame
    table.to_world = [&c = *calibration, height = a.height](const std::vector<cv::Point2d>& px) {
      std::vector<Eigen::Vector2d> in;
      in.reserve(px.size());
      for (const auto& p : px) in.emplace_back(p.x, p.y);
      std::vector<cv::Point2d> out;
      for (const auto& w : calib::to_world_at_height(c, in, height)) out.emplace_back(w.x(), w.y());
      return out;
    };
  }
  if (!a.format.empty()) {
    table.format = a.format == "jsonl" ? io::TableFormat::jsonl : io::TableFormat::csv;
  } else if (!a.out.empty()) {
    const auto f = io::table_format_for(a.out);
    if (!f) throw UsageError{"--out " + a.out + ": unknown table format (use .csv or .jsonl, or give --format)"};
    table.format = *f;
  }
  auto writer = a.out.empty() ? std::make_unique<io::BlobTableWriter>(std::cout, table)
                              : std::make_unique<io::BlobTableWriter>(a.out, table);
  std::optional<io::Annotator> annotator;
  if (!a.annotate.empty()) {
    const auto count = source->frame_count();
    annotator.emplace(a.annotate, a.fps > 0 ? a.fps : source->fps(), count && *count == 1);
  }

  pl::StreamOptions opts;
  opts.executor.threads = a.threads;
  opts.executor.frames_in_flight = a.frames_in_flight;
  opts.realtime = a.realtime;
  opts.fps = a.fps;
  opts.stop = &g_stop_requested;
  ProgressBar bar("neopipe run", source->frame_count(), !a.quiet);
  opts.progress = [&](const pl::RunStats& s) {
    bar.update(s.frames_read, fmt::format("{:.0f} frames/s", s.frames_per_second()));
  };

  g_stop_requested = false;
  g_stop_signal = 0;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  pl::RunStats stats;
  int code = kExitOk;
  std::string error;
  try {
    pl::run_stream(
        *source, std::move(graph), opts,
        [&](const pl::FrameResult& r) {
          const auto& blobs = std::get<pl::BlobList>(r.outputs[*blob_output]);
          if (calibration && calibration->image_size.area() > 0 && r.input.size() != calibration->image_size) {
            throw std::runtime_error(fmt::format("{}: made for {}x{} images, but frame {} of {} is {}x{}", a.calib,
                                                 calibration->image_size.width, calibration->image_size.height, r.index,
                                                 source->description(), r.input.cols, r.input.rows));
          }
          writer->write(r.index, blobs);
          if (annotator) annotator->write(r.index, r.input, blobs);
        },
        stats);
    if (annotator) annotator->close();
  } catch (const std::exception& e) {
    code = kExitFailure;
    error = e.what();
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  bar.clear();
  if (!a.quiet) fmt::print(stderr, "neopipe run: {}: {}\n", source->description(), stats.summary());
  if (code != kExitOk) {
    print_error("run", error);
    return code;
  }
  if (!stats.interrupted) return kExitOk;
  return g_stop_signal == SIGTERM ? kExitTerminated : kExitInterrupted;
}

}  // namespace neopipe::apps
