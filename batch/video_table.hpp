#pragma once
// One input through the blob graph into its blob table: what `neopipe run INPUT --out TABLE` does,
// with the table options a batch manifest holds, so a merged batch table equals `neopipe run` on
// each file.

#include <cstdint>
#include <filesystem>
#include <string>

#include "batch/manifest.hpp"

namespace neopipe::batch {

struct TableStats {
  std::int64_t frames = 0;
  std::int64_t blobs = 0;
  double seconds = 0;  ///< wall time of the run
};

/// Runs `input` with `options` and writes its table to `table` (truncated). `threads` 0: all cores.
/// Throws (std::exception) for an unreadable input or graph, or a failed write; the table may then
/// hold the rows of the frames before the error.
TableStats write_blob_table(const std::string& input, const TableRunOptions& options,
                            const std::filesystem::path& table, int threads);

}  // namespace neopipe::batch
