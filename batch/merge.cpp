#include "batch/merge.hpp"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "batch/atomic_file.hpp"
#include "batch/shard_runner.hpp"

namespace neopipe::batch {
namespace fs = std::filesystem;

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

BatchSummary summarise_batch(const Manifest& m) {
  BatchSummary s;
  for (const ManifestInput& in : m.inputs) {
    ++s.inputs;
    const InputStatus st = input_status(m, in);
    switch (st.state) {
      case InputState::done:
        ++s.done;
        s.frames += st.frames;
        s.blobs += st.blobs;
        s.seconds += st.seconds;
        break;
      case InputState::failed:
        ++s.failed;
        s.failures.emplace_back(in.path, st.error);
        break;
      case InputState::pending:
        ++s.pending;
        break;
    }
  }
  return s;
}

BatchSummary merge_tables(const Manifest& m, const fs::path& out, bool partial) {
  const std::string ext = out.extension().string();
  const std::string format = ext == ".jsonl" || ext == ".ndjson" ? "jsonl" : ext == ".csv" ? "csv" : "";
  if (format.empty()) throw BatchError(fmt::format("--out {}: use a .csv or .jsonl file", out.string()));
  if (format != m.options.format) {
    throw BatchError(fmt::format("--out {}: the batch's tables are {} (planned with --format {})", out.string(),
                                 m.options.format, m.options.format));
  }
  BatchSummary s = summarise_batch(m);
  if (s.pending > 0 && !partial) {
    throw BatchError(fmt::format("{} of {} inputs are not done yet (neopipe batch status; --partial merges what is)",
                                 s.pending, s.inputs));
  }
  const fs::path tmp = temporary_path_for(out);
  {
    std::ofstream merged(tmp, std::ios::binary | std::ios::trunc);
    if (!merged) throw BatchError(fmt::format("--out {}: cannot create {}", out.string(), tmp.string()));
    std::string header;
    for (const ManifestInput& in : m.inputs) {
      if (input_status(m, in).state != InputState::done) continue;
      std::ifstream table(m.table_path(in), std::ios::binary);
      std::string line;
      bool first = true;
      const std::string field = format == "csv" ? csv_field(in.path) : nlohmann::json(in.path).dump();
      while (std::getline(table, line)) {
        if (format == "csv" && first) {
          first = false;
          if (header.empty()) {
            header = line;
            merged << "input," << line << '\n';
          } else if (line != header) {
            throw BatchError(fmt::format("{}: its columns ({}) differ from the first table's ({})",
                                         m.table_path(in).string(), line, header));
          }
          continue;
        }
        if (format == "csv") {
          merged << field << ',' << line << '\n';
        } else if (line.size() > 1 && line.front() == '{') {
          merged << "{\"input\":" << field << (line[1] == '}' ? "" : ",") << line.substr(1) << '\n';
        }
      }
      if (table.bad()) throw BatchError(fmt::format("{}: read failed", m.table_path(in).string()));
    }
    merged.flush();
    if (!merged) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw BatchError(fmt::format("--out {}: write failed", out.string()));
    }
  }
  std::error_code ec;
  fs::rename(tmp, out, ec);
  if (ec) throw BatchError(fmt::format("--out {}: cannot rename into place: {}", out.string(), ec.message()));
  return s;
}

}  // namespace neopipe::batch
