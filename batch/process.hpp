#pragma once
// Running a program (sbatch, squeue, sacct) and collecting its output, with a time limit so that a
// scheduler that does not answer cannot hang the command.

#include <string>
#include <vector>

namespace neopipe::batch {

struct ProcessResult {
  bool started = false;  ///< false: not found on PATH (or not executable)
  bool timed_out = false;
  int exit_code = -1;  ///< -1 when killed by a signal
  std::string out;
  std::string err;
};

/// Runs argv[0] (searched on PATH) with stdin from /dev/null; kills it after `timeout_seconds`.
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds);

/// Whether `program` is an executable on PATH.
bool on_path(const std::string& program);

}  // namespace neopipe::batch
