#include "batch/video_table.hpp"

#include <fmt/format.h>

#include <variant>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/io/blob_table_writer.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/stream_runner.hpp"

namespace neopipe::batch {
namespace pl = neopipe::pipeline;
namespace io = neopipe::pipeline::io;

namespace {

// As `neopipe run` without --annotate (apps/run_command.cpp run_graph): the built-in graph reads
// gray frames (a video's luma plane), so the tables agree with it byte for byte.
pl::GraphSpec batch_graph(const TableRunOptions& o) {
  if (!o.graph.empty()) return pl::load_graph_spec(o.graph);
  pl::BlobGraphOptions b;
  if (!o.threshold.empty() && o.threshold != "otsu") b.threshold = std::stoi(o.threshold);
  b.connectivity = o.connectivity;
  b.source = pl::PortType::gray8;
  return pl::blob_graph(b);
}

}  // namespace

TableStats write_blob_table(const std::string& input, const TableRunOptions& options,
                            const std::filesystem::path& table, int threads) {
  pl::CompiledGraph graph = pl::compile(batch_graph(options), pl::standard_kernels());
  const auto blob_output = graph.find_output(pl::PortType::blobs);
  if (!blob_output) throw std::runtime_error(fmt::format("{}: the graph has no blobs output", graph.origin()));
  if (graph.source_type() == pl::PortType::s16) {
    throw std::runtime_error(
        fmt::format("{}: the graph's source takes s16 frames, which files do not hold", graph.origin()));
  }
  const auto source = io::open_frame_source(
      {input}, graph.source_type() == pl::PortType::bgr8 ? io::ColorFormat::bgr : io::ColorFormat::gray);
  io::TableOptions t;
  t.moments = options.moments;
  t.format = options.format == "jsonl" ? io::TableFormat::jsonl : io::TableFormat::csv;
  io::BlobTableWriter writer(table.string(), t);
  pl::StreamOptions opts;
  opts.executor.threads = threads;
  pl::RunStats stats;
  pl::run_stream(
      *source, std::move(graph), opts,
      [&](const pl::FrameResult& r) { writer.write(r.index, std::get<pl::BlobList>(r.outputs[*blob_output])); }, stats);
  return {stats.frames_processed, stats.blobs, stats.seconds};
}

}  // namespace neopipe::batch
