#include "batch/shard.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace neopipe::batch {
namespace {

// The whole of `text` as a non-negative integer, or -1.
std::int64_t whole_number_or_minus_one(std::string_view text) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size() || v < 0) return -1;
  return v;
}

}  // namespace

ShardSpec parse_shard(const std::string& text, const std::string& option) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) {
    throw std::invalid_argument(fmt::format("{} {}: expected I/K (shard I of K, I from 0 to K-1)", option, text));
  }
  const std::int64_t index = whole_number_or_minus_one(std::string_view(text).substr(0, slash));
  const std::int64_t count = whole_number_or_minus_one(std::string_view(text).substr(slash + 1));
  if (index < 0 || count < 1) {
    throw std::invalid_argument(fmt::format("{} {}: expected I/K with whole numbers I >= 0, K >= 1", option, text));
  }
  if (index >= count) {
    throw std::invalid_argument(fmt::format("{} {}: shard index out of range (0 to {})", option, text, count - 1));
  }
  return {index, count};
}

ItemRange shard_range(std::int64_t items, const ShardSpec& spec) {
  if (spec.count < 1 || spec.index < 0 || spec.index >= spec.count || items < 0) {
    throw std::invalid_argument(fmt::format("shard {}/{} of {} items: out of range", spec.index, spec.count, items));
  }
  // The first N mod K blocks hold one item more: sizes differ by at most one and the blocks tile 0..N.
  const std::int64_t base = items / spec.count;
  const std::int64_t extra = items % spec.count;
  const auto start = [&](std::int64_t i) { return i * base + std::min(i, extra); };
  return {start(spec.index), start(spec.index + 1)};
}

}  // namespace neopipe::batch
