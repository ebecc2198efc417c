#pragma once
// `neopipe batch merge`: every done input's table, in manifest order, as one table with an `input`
// column first (the input's absolute path), and a summary of the batch. Rows are the per-input
// tables' bytes unchanged, so the merge of a batch equals `neopipe run` on each file.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "batch/manifest.hpp"

namespace neopipe::batch {

struct BatchSummary {
  std::int64_t inputs = 0;
  std::int64_t done = 0;
  std::int64_t failed = 0;
  std::int64_t pending = 0;
  std::int64_t frames = 0;  ///< of the done inputs
  std::int64_t blobs = 0;
  double seconds = 0;  ///< processing wall time summed over the done inputs (not the batch's elapsed time)
  std::vector<std::pair<std::string, std::string>> failures;  ///< input, its error line
};

/// The summary from the markers alone.
BatchSummary summarise_batch(const Manifest& manifest);

/// Writes the merged table to `out` (csv or jsonl by its extension, which must match the manifest's
/// format) through a temporary file and a rename. Failed inputs are left out (and listed in the
/// summary). Pending inputs are an error unless `partial`. Throws BatchError.
BatchSummary merge_tables(const Manifest& manifest, const std::filesystem::path& out, bool partial);

/// "input" as a CSV field: quoted (with doubled quotes) when it holds a comma, quote or newline.
std::string csv_field(const std::string& text);

}  // namespace neopipe::batch
