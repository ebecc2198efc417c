#pragma once
// `neopipe run`: frames from a video or images through a graph, out as a blob table.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

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
  bool quiet = false;
  bool list_kernels = false;
};

/// Declares the subcommand's options on `parent`; returns the subcommand.
CLI::App* add_run_command(CLI::App& parent, RunArgs& args);
/// Runs it; returns the process exit code.
int run_command(const RunArgs& args);

}  // namespace neopipe::apps
