#include "batch/stats_shards.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <map>

#include "batch/manifest.hpp"

namespace neopipe::batch {

std::string shard_table_line(const ShardSpec& spec, const ItemRange& rows, std::int64_t total_rows) {
  return fmt::format("# neopipe shard {}/{} rows {}-{} of {}\n", spec.index, spec.count, rows.first, rows.last,
                     total_rows);
}

std::vector<GridRun> grid_runs(std::size_t outer, std::size_t inner, const ItemRange& range) {
  std::vector<GridRun> runs;
  if (inner == 0) return runs;
  for (auto cell = static_cast<std::size_t>(range.first);
       cell < static_cast<std::size_t>(range.last) && cell < outer * inner;) {
    const std::size_t o = cell / inner;
    const std::size_t first = cell % inner;
    const std::size_t last = std::min(inner, first + (static_cast<std::size_t>(range.last) - cell));
    runs.push_back({o, first, last});
    cell += last - first;
  }
  return runs;
}

std::string merge_shard_tables(const std::vector<std::string>& texts, const std::vector<std::string>& names) {
  struct Part {
    long long first = 0;
    long long last = 0;
    std::string header;
    std::string rows;
    std::string name;
  };
  std::map<long long, Part> parts;
  long long count = -1;
  long long total = -1;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string& t = texts[i];
    const std::string& name = i < names.size() ? names[i] : fmt::format("table {}", i);
    const auto nl = t.find('\n');
    long long index = 0;
    long long k = 0;
    Part p;
    long long n = 0;
    if (nl == std::string::npos ||
        std::sscanf(t.substr(0, nl).c_str(), "# neopipe shard %lld/%lld rows %lld-%lld of %lld", &index, &k, &p.first,
                    &p.last, &n) != 5) {
      throw BatchError(fmt::format("{}: not a shard's table (no \"# neopipe shard I/K\" first line)", name));
    }
    if (count >= 0 && (k != count || n != total)) {
      throw BatchError(fmt::format("{}: shard {}/{} of {} rows, but the others are of {} shards and {} rows", name,
                                   index, k, n, count, total));
    }
    count = k;
    total = n;
    const auto header_end = t.find('\n', nl + 1);
    p.header = t.substr(nl + 1, header_end == std::string::npos ? std::string::npos : header_end - nl);
    p.rows = header_end == std::string::npos ? "" : t.substr(header_end + 1);
    p.name = name;
    if (!parts.empty() && parts.begin()->second.header != p.header) {
      throw BatchError(fmt::format("{}: its columns differ from {}'s", name, parts.begin()->second.name));
    }
    if (parts.count(index))
      throw BatchError(fmt::format("{}: shard {}/{} given twice (also {})", name, index, k, parts[index].name));
    parts.emplace(index, p);
  }
  if (parts.empty()) throw BatchError("no shard tables given");
  std::string merged = parts.begin()->second.header;
  long long expect = 0;
  for (long long i = 0; i < count; ++i) {
    const auto it = parts.find(i);
    if (it == parts.end()) throw BatchError(fmt::format("shard {}/{} is missing", i, count));
    if (it->second.first != expect) {
      throw BatchError(fmt::format("{}: rows {}-{} do not follow row {}", it->second.name, it->second.first,
                                   it->second.last, expect));
    }
    expect = it->second.last;
    merged += it->second.rows;
  }
  if (expect != total) throw BatchError(fmt::format("the shards hold rows 0-{} of {}", expect, total));
  return merged;
}

}  // namespace neopipe::batch
