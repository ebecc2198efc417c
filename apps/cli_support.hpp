#pragma once
// What every subcommand shares: exit codes, one-line error reporting, and the options that several
// subcommands take.

#include <string>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace neopipe::apps {

enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,        ///< bad input, failed processing
  kExitUsage = 2,          ///< bad command line
  kExitUnreachable = 3,    ///< neopipe map: the goal cannot be reached from the start
  kExitInterrupted = 130,  ///< stopped by Ctrl-C after finishing the frames in flight
  kExitTerminated = 143    ///< stopped by SIGTERM after finishing the frames in flight (128 + 15)
};

/// Prints "neopipe COMMAND: error: MESSAGE" as one line on stderr (newlines in MESSAGE become spaces).
void print_error(const std::string& command, const std::string& message);

/// `--cost NAME` on `cmd` into `cost`: one of the planner's criteria (`neopipe map`, `neopipe nav`).
CLI::Option* add_cost_option(CLI::App* cmd, std::string& cost);

/// Thrown for a bad command line found after parsing (conflicting options and such).
struct UsageError {
  std::string message;
};

}  // namespace neopipe::apps
