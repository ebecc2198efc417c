#pragma once
// Shards: splitting N independent items (videos, journeys, statistics rows) among K cluster tasks by
// a rule that depends on N and K only, so every task computes its own share without talking to
// the others, and a merge can check that the shards it is given cover the whole exactly once.

#include <cstdint>
#include <string>

namespace neopipe::batch {

/// Shard `index` of `count` (0 <= index < count).
struct ShardSpec {
  std::int64_t index = 0;
  std::int64_t count = 1;
};

/// Parses "I/K" (the command line's --shard). Throws std::invalid_argument naming `option` and the
/// text for anything else, K < 1, or I outside 0..K-1.
ShardSpec parse_shard(const std::string& text, const std::string& option = "--shard");

/// Items [first, last) of `items` that shard `spec` takes: contiguous blocks whose sizes differ by
/// at most one, in order (shard 0 first). Contiguous, so a merge is a concatenation.
struct ItemRange {
  std::int64_t first = 0;
  std::int64_t last = 0;
  [[nodiscard]] std::int64_t size() const { return last - first; }
};
ItemRange shard_range(std::int64_t items, const ShardSpec& spec);

}  // namespace neopipe::batch
