#pragma once
// `neopipe run`: frames from a video or images through a graph, out as a blob table.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::apps {

struct RunArgs {
  std::vector<std::string> inputs;
  std::string graph;
  std::string threshold;  ///< empty: Otsu per frame
  int connectivity = 0;   ///< 0: not given (8)
  std::string out;
  std::string format;
  std::string annotate;
  bool realtime = false;
  double fps = 0;
  int threads = 0;
  int frames_in_flight = 0;
  bool moments = false;
  std::string calib;  ///< calibration file: add X,Y (workspace mm) to every row
  double height = 0;  ///< mm above the calibrated plane where the blobs' centres lie
  bool quiet = false;
  bool list_kernels = false;
};

/// Declares the subcommand's options on `parent`; returns the subcommand.
CLI::App* add_run_command(CLI::App& parent, RunArgs& args);
/// Runs it; returns the process exit code.
int run_command(const RunArgs& args);

/// The graph `neopipe run` runs for `args`: --graph's spec, else the built-in blob graph as
/// --threshold and --connectivity configure it, reading gray frames, or BGR ones with --annotate
/// (which draws on them). `neopipe bench --video` runs it with RunArgs{}.
/// Throws UsageError for --threshold or --connectivity together with --graph.
pipeline::GraphSpec run_graph(const RunArgs& args);
/// The pixel format `neopipe run` reads frames in for `graph`: BGR for a bgr8 source, else gray.
pipeline::io::ColorFormat run_source_format(const pipeline::CompiledGraph& graph);

}  // namespace neopipe::apps
