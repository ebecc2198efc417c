#pragma once
// The batch manifest (`neopipe batch plan`): every input of an archive, sorted, checksummed and
// assigned to a shard, with the options every shard runs them with. One JSON file, written once into
// the output folder, read by every cluster task. docs/cluster.md describes the fields.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace neopipe::batch {

/// How each input becomes a table: the options of `neopipe run` that change the table.
struct TableRunOptions {
  std::string graph;           ///< graph spec (absolute path); empty: the built-in blob graph
  std::string graph_checksum;  ///< of the graph file: a graph edited after planning is noticed
  std::string threshold;       ///< built-in graph: a fixed threshold 0..255; empty: Otsu per frame
  int connectivity = 8;        ///< built-in graph
  bool moments = false;
  std::string format = "csv";  ///< csv | jsonl
};

struct ManifestInput {
  std::string path;      ///< absolute
  std::string checksum;  ///< file_checksum at planning
  std::int64_t bytes = 0;
  std::int64_t shard = 0;
  std::string key;  ///< file stem of its outputs: "000012-name"
};

struct Manifest {
  std::string neopipe_version;
  std::string id;   ///< checksum of everything else: two manifests are the same iff their ids are
  std::string out;  ///< output folder (absolute)
  std::int64_t shards = 1;
  TableRunOptions options;
  std::vector<ManifestInput> inputs;  ///< sorted by path

  [[nodiscard]] std::filesystem::path manifest_path() const { return std::filesystem::path(out) / "manifest.json"; }
  [[nodiscard]] std::filesystem::path table_path(const ManifestInput& in) const;
  [[nodiscard]] std::filesystem::path done_path(const ManifestInput& in) const;
  [[nodiscard]] std::filesystem::path failed_path(const ManifestInput& in) const;
  /// The inputs of shard `shard`, in manifest order.
  [[nodiscard]] std::vector<const ManifestInput*> shard_inputs(std::int64_t shard) const;
  /// Checksum of the options: part of every done-marker.
  [[nodiscard]] std::string options_checksum() const;
};

/// A bad manifest, a changed input, a foreign output folder, a shard out of range: the user's to
/// fix. The message is one line naming the file and the cause.
class BatchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The inputs named on the command line: files as given, directories searched (recursively) for
/// videos, and list files (*.txt, *.list, *.lst: one path per line, relative to the list's folder;
/// blank lines and # comments skipped). Absolute, without duplicates, sorted byte-wise. Throws
/// BatchError for a missing input or none at all.
std::vector<std::string> expand_inputs(const std::vector<std::string>& names);

struct PlanRequest {
  std::vector<std::string> inputs;  ///< as given: files, directories, list files
  std::string out;
  std::int64_t shards = 1;
  TableRunOptions options;
  std::function<void(std::int64_t done, std::int64_t total)> progress;  ///< checksummed so far
};

/// Builds the manifest: inputs expanded and sorted, input i in shard i mod N (neighbours in name,
/// often alike in size, go to different shards), checksummed. Throws BatchError for bad input.
Manifest plan_manifest(const PlanRequest& request);

/// Writes the manifest into its output folder (creating it) by temp-file-and-rename. An output
/// folder that holds another manifest (another id) is refused: its tables would mix. The same
/// manifest again is no change. Returns true if the file was written, false if it was there already.
bool write_manifest(const Manifest& manifest);

/// Reads and checks a manifest: its format, its id against its content (no hand edits), and that it
/// was made by this neopipe version. Throws BatchError naming `path` and the cause.
Manifest load_manifest(const std::filesystem::path& path);

nlohmann::json manifest_json(const Manifest& manifest);
/// Reads a manifest's JSON without the version and id checks (for tests and status of old folders).
Manifest manifest_from_json(const nlohmann::json& j);
/// The id of `manifest` as its content determines it (the `id` field itself left out).
std::string manifest_id(const Manifest& manifest);

}  // namespace neopipe::batch
