#pragma once
// `neopipe batch`: video archives on a Slurm cluster (docs/cluster.md). plan -> submit (or run a
// shard by hand) -> status -> merge; and merge-shards for `nav --trials --shard` and `map stats
// --shard` outputs.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace neopipe::apps {

struct BatchArgs {
  // plan
  std::vector<std::string> inputs;
  std::string out;
  std::int64_t shards = 1;
  std::string graph;
  std::string threshold;
  int connectivity = 8;
  bool moments = false;
  std::string format = "csv";
  // run, submit, status, merge
  std::string manifest;
  std::int64_t shard = -1;
  int threads = 0;
  std::string partition;
  std::string time;
  std::string mem;
  std::int64_t max_parallel = 0;
  int cpus_per_task = 1;
  bool dry_run = false;
  bool all_shards = false;
  bool partial = false;
  bool json = false;
  bool quiet = false;
  // merge-shards
  std::vector<std::string> shard_files;
};

/// Declares `batch` and its subcommands on `app`; returns `batch`.
CLI::App* add_batch_command(CLI::App& app, BatchArgs& args);
/// Runs the subcommand given; returns the process exit code.
int batch_command(const CLI::App& batch, const BatchArgs& args);

}  // namespace neopipe::apps
