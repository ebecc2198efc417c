#include "batch/shard_runner.hpp"

#include <fmt/format.h>

#include <fstream>

#include "batch/atomic_file.hpp"
#include "batch/checksum.hpp"
#include "batch/video_table.hpp"
#include "neopipe_version.hpp"

namespace neopipe::batch {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::optional<json> read_marker(const fs::path& p) {
  std::ifstream in(p);
  if (!in) return std::nullopt;
  try {
    return json::parse(in);
  } catch (const std::exception&) {
    return std::nullopt;  // a marker is written whole by a rename: unreadable means not ours
  }
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

void check_shard_index(const Manifest& m, std::int64_t shard) {
  if (shard < 0 || shard >= m.shards) {
    throw BatchError(fmt::format("--shard {}: out of range: the manifest has {} shard{} (0 to {})", shard, m.shards,
                                 m.shards == 1 ? "" : "s", m.shards - 1));
  }
}

void check_output_folder(const Manifest& m) {
  const auto there = read_marker(m.manifest_path());
  if (!there) {
    throw BatchError(fmt::format("{}: missing or unreadable: the output folder was not planned (neopipe batch plan)",
                                 m.manifest_path().string()));
  }
  const std::string id = there->value("id", "");
  if (id != m.id) {
    throw BatchError(
        fmt::format("--out {}: holds another manifest (id {}, this one {}): nothing written", m.out, id, m.id));
  }
}

InputStatus input_status(const Manifest& m, const ManifestInput& in) {
  InputStatus s;
  if (const auto done = read_marker(m.done_path(in))) {
    const bool matches = done->value("manifest", "") == m.id && done->value("checksum", "") == in.checksum &&
                         done->value("options", "") == m.options_checksum() &&
                         done->value("neopipe_version", "") == m.neopipe_version;
    if (matches && fs::exists(m.table_path(in))) {
      s.state = InputState::done;
      s.frames = done->value("frames", std::int64_t{0});
      s.blobs = done->value("blobs", std::int64_t{0});
      s.seconds = done->value("seconds", 0.0);
      return s;
    }
  }
  if (const auto failed = read_marker(m.failed_path(in))) {
    if (failed->value("manifest", "") == m.id) {
      s.state = InputState::failed;
      s.error = failed->value("error", "");
    }
  }
  return s;
}

ShardReport run_shard(const Manifest& m, std::int64_t shard, const ShardRunOptions& options) {
  check_shard_index(m, shard);
  check_output_folder(m);
  ShardReport report;
  for (const ManifestInput* in : m.shard_inputs(shard)) {
    ++report.inputs;
    InputStatus status = input_status(m, *in);
    if (status.state == InputState::done) {
      ++report.skipped;
      if (options.on_input) options.on_input(*in, status, true);
      continue;
    }
    const fs::path table = m.table_path(*in);
    remove_stale_temporaries(table);
    const fs::path tmp = temporary_path_for(table);
    json marker = {{"input", in->path},
                   {"checksum", in->checksum},
                   {"options", m.options_checksum()},
                   {"neopipe_version", std::string(neopipe::version)},
                   {"manifest", m.id}};
    try {
      const std::string now = file_checksum(in->path);
      if (now != in->checksum) {
        throw BatchError(fmt::format("{}: changed since planning (checksum {}, the manifest's {}): plan again",
                                     in->path, now, in->checksum));
      }
      if (!m.options.graph.empty() && file_checksum(m.options.graph) != m.options.graph_checksum) {
        throw BatchError(fmt::format("{}: the graph changed since planning: plan again", m.options.graph));
      }
      const TableStats t = write_blob_table(in->path, m.options, tmp, options.threads);
      fs::rename(tmp, table);
      marker["frames"] = t.frames;
      marker["blobs"] = t.blobs;
      marker["seconds"] = t.seconds;
      write_file_atomically(m.done_path(*in), marker.dump() + "\n");
      std::error_code ignored;
      fs::remove(m.failed_path(*in), ignored);  // failed before, done now
      status = {InputState::done, "", t.frames, t.blobs, t.seconds};
      ++report.done;
      report.frames += t.frames;
      report.seconds += t.seconds;
    } catch (const std::exception& e) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      status = {InputState::failed, one_line(e.what()), 0, 0, 0};
      marker["error"] = status.error;
      write_file_atomically(m.failed_path(*in), marker.dump() + "\n");
      ++report.failed;
    }
    if (options.on_input) options.on_input(*in, status, false);
  }
  return report;
}

}  // namespace neopipe::batch
