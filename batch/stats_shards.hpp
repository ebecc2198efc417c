#pragma once
// Sharded tables of independent rows (`neopipe map stats --shard I/K`): each shard computes a
// contiguous block of the rows and writes them under a first line
// "# neopipe shard I/K rows A-B of N"; the merge checks that the shards given are all K of one run,
// each once, and concatenates their rows in order under one header. The rows of a shard are the
// bytes the unsharded run writes for them, so the merge is byte-identical to that run.

#include <cstddef>
#include <string>
#include <vector>

#include "batch/shard.hpp"

namespace neopipe::batch {

/// The first line of a shard's table (with its newline).
std::string shard_table_line(const ShardSpec& spec, const ItemRange& rows, std::int64_t total_rows);

/// The cells of a rows x columns grid (row-major: `outer` outer, `inner` inner, as map stats orders
/// windows and populations) in `range`, as runs of one outer index: {outer, inner_first, inner_last}.
struct GridRun {
  std::size_t outer = 0;
  std::size_t inner_first = 0;
  std::size_t inner_last = 0;  ///< one past
};
std::vector<GridRun> grid_runs(std::size_t outer, std::size_t inner, const ItemRange& range);

/// Merges the shard tables' texts (any order): throws BatchError (naming the file, `names[i]`) when
/// one lacks the shard line, when they come from different runs (K, N or header differ), or when a
/// shard is missing or given twice. Returns the merged table.
std::string merge_shard_tables(const std::vector<std::string>& texts, const std::vector<std::string>& names);

}  // namespace neopipe::batch
