#pragma once
// `neopipe batch run --shard I`: the inputs of one shard, each into its own table. Resumable: an
// input whose done-marker matches (same input checksum, options, neopipe version, manifest) is
// skipped; a table appears only whole (temp file and rename) and only then its marker, so a task
// killed at any point leaves each input either done or to do. An input that fails (corrupt, changed
// since planning) gets a failed-marker with its error line, and the shard goes on.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "batch/manifest.hpp"

namespace neopipe::batch {

enum class InputState { pending, done, failed };

struct InputStatus {
  InputState state = InputState::pending;
  std::string error;  ///< failed: the error line
  std::int64_t frames = 0;
  std::int64_t blobs = 0;
  double seconds = 0;
};

/// What the markers in the output folder say about `input`. A done-marker counts only when it
/// matches the manifest (id, input checksum, options, version) and the table exists.
InputStatus input_status(const Manifest& manifest, const ManifestInput& input);

struct ShardReport {
  std::int64_t inputs = 0;
  std::int64_t skipped = 0;  ///< done before (resumed past)
  std::int64_t done = 0;     ///< done now
  std::int64_t failed = 0;
  std::int64_t frames = 0;  ///< of the inputs done now
  double seconds = 0;       ///< of the inputs done now
};

struct ShardRunOptions {
  int threads = 0;  ///< per input; 0: all cores
  /// Called after each input with its manifest entry and status (skipped inputs: done, seconds 0).
  std::function<void(const ManifestInput&, const InputStatus&, bool skipped)> on_input;
};

/// Runs shard `shard` of `manifest`. Throws BatchError when the shard is out of range or the output
/// folder belongs to another manifest; input failures are recorded, not thrown.
ShardReport run_shard(const Manifest& manifest, std::int64_t shard, const ShardRunOptions& options);

/// Throws BatchError unless `shard` is one of the manifest's shards.
void check_shard_index(const Manifest& manifest, std::int64_t shard);
/// Throws BatchError unless the manifest in the output folder is `manifest` (same id).
void check_output_folder(const Manifest& manifest);

}  // namespace neopipe::batch
