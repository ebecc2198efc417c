#include "batch/manifest.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "batch/atomic_file.hpp"
#include "batch/checksum.hpp"
#include "neopipe_version.hpp"

namespace neopipe::batch {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kManifestFormat = "neopipe-batch-manifest";
constexpr int kManifestFormatVersion = 1;

bool is_list_file(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".txt" || ext == ".list" || ext == ".lst";
}

bool is_video_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::set<std::string> kVideo = {".mp4",  ".avi", ".mkv", ".mov", ".webm", ".m4v", ".mpg",
                                               ".mpeg", ".ts",  ".wmv", ".flv", ".y4m",  ".ogv"};
  return kVideo.count(ext) > 0;
}

void add_input(const fs::path& p, const std::string& named_by, std::set<std::string>& out);

void add_list_file(const fs::path& list, std::set<std::string>& out) {
  std::ifstream in(list);
  if (!in) throw BatchError(fmt::format("{}: cannot read this list file", list.string()));
  std::string line;
  std::int64_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto last = line.find_last_not_of(" \t\r");
    fs::path p = line.substr(first, last - first + 1);
    if (p.is_relative()) p = list.parent_path() / p;
    add_input(p, fmt::format("{} line {}", list.string(), number), out);
  }
}

void add_input(const fs::path& p, const std::string& named_by, std::set<std::string>& out) {
  std::error_code ec;
  const auto status = fs::status(p, ec);
  if (ec || !fs::exists(status)) throw BatchError(fmt::format("{}: no such file or directory{}", p.string(), named_by));
  if (fs::is_directory(status)) {
    for (const auto& entry : fs::recursive_directory_iterator(p, fs::directory_options::follow_directory_symlink)) {
      if (entry.is_regular_file() && is_video_file(entry.path()))
        out.insert(fs::absolute(entry.path()).lexically_normal());
    }
    return;
  }
  if (named_by.empty() && is_list_file(p)) {
    add_list_file(fs::absolute(p), out);
    return;
  }
  out.insert(fs::absolute(p).lexically_normal().string());
}

std::string key_of(std::size_t index, const std::string& path) {
  std::string stem = fs::path(path).stem().string();
  for (char& c : stem) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  return fmt::format("{:06}-{}", index, stem.substr(0, 80));
}

json options_json(const TableRunOptions& o) {
  return {{"graph", o.graph},         {"graph_checksum", o.graph_checksum},
          {"threshold", o.threshold}, {"connectivity", o.connectivity},
          {"moments", o.moments},     {"format", o.format}};
}

}  // namespace

fs::path Manifest::table_path(const ManifestInput& in) const {
  return fs::path(out) / "tables" / (in.key + (options.format == "jsonl" ? ".jsonl" : ".csv"));
}
fs::path Manifest::done_path(const ManifestInput& in) const {
  return fs::path(out) / "done" / (in.key + ".json");
}
fs::path Manifest::failed_path(const ManifestInput& in) const {
  return fs::path(out) / "failed" / (in.key + ".json");
}

std::vector<const ManifestInput*> Manifest::shard_inputs(std::int64_t shard) const {
  std::vector<const ManifestInput*> mine;
  for (const ManifestInput& in : inputs)
    if (in.shard == shard) mine.push_back(&in);
  return mine;
}

std::string Manifest::options_checksum() const {
  return text_checksum(options_json(options).dump());
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& names) {
  std::set<std::string> out;  // sorted byte-wise, duplicates gone
  for (const std::string& n : names) add_input(n, "", out);
  if (out.empty()) throw BatchError("no inputs: the files, folders and lists given hold no video");
  return {out.begin(), out.end()};
}

Manifest plan_manifest(const PlanRequest& r) {
  if (r.shards < 1) throw BatchError(fmt::format("--shards {}: must be at least 1", r.shards));
  if (r.out.empty()) throw BatchError("--out: an output folder is needed");
  if (r.options.format != "csv" && r.options.format != "jsonl") {
    throw BatchError(fmt::format("--format {}: use csv or jsonl", r.options.format));
  }
  Manifest m;
  m.neopipe_version = neopipe::version;
  m.out = fs::absolute(r.out).lexically_normal().string();
  while (m.out.size() > 1 && m.out.back() == '/') m.out.pop_back();
  m.shards = r.shards;
  m.options = r.options;
  if (!m.options.graph.empty()) {
    m.options.graph = fs::absolute(m.options.graph).lexically_normal().string();
    m.options.graph_checksum = file_checksum(m.options.graph);
  }
  const std::vector<std::string> paths = expand_inputs(r.inputs);
  if (std::ssize(paths) < r.shards) {
    throw BatchError(fmt::format("--shards {}: more shards than the {} inputs", r.shards, paths.size()));
  }
  for (std::size_t i = 0; i < paths.size(); ++i) {
    ManifestInput in;
    in.path = paths[i];
    in.bytes = static_cast<std::int64_t>(fs::file_size(paths[i]));
    in.checksum = file_checksum(paths[i]);
    in.shard = static_cast<std::int64_t>(i) % r.shards;
    in.key = key_of(i, paths[i]);
    m.inputs.push_back(in);
    if (r.progress) r.progress(static_cast<std::int64_t>(i + 1), std::ssize(paths));
  }
  m.id = manifest_id(m);
  return m;
}

json manifest_json(const Manifest& m) {
  json inputs = json::array();
  for (const ManifestInput& in : m.inputs) {
    inputs.push_back(
        {{"path", in.path}, {"checksum", in.checksum}, {"bytes", in.bytes}, {"shard", in.shard}, {"key", in.key}});
  }
  return {{"format", kManifestFormat},
          {"format_version", kManifestFormatVersion},
          {"neopipe_version", m.neopipe_version},
          {"id", m.id},
          {"out", m.out},
          {"shards", m.shards},
          {"options", options_json(m.options)},
          {"inputs", inputs}};
}

std::string manifest_id(const Manifest& m) {
  json j = manifest_json(m);
  j.erase("id");
  return text_checksum(j.dump());
}

Manifest manifest_from_json(const json& j) {
  if (!j.is_object() || j.value("format", "") != kManifestFormat) {
    throw BatchError(R"(not a neopipe batch manifest (no "format": "neopipe-batch-manifest"))");
  }
  if (j.at("format_version").get<int>() != kManifestFormatVersion) {
    throw BatchError(fmt::format("manifest format version {}; this neopipe reads version {}",
                                 j.at("format_version").get<int>(), kManifestFormatVersion));
  }
  Manifest m;
  m.neopipe_version = j.at("neopipe_version").get<std::string>();
  m.id = j.at("id").get<std::string>();
  m.out = j.at("out").get<std::string>();
  m.shards = j.at("shards").get<std::int64_t>();
  const json& o = j.at("options");
  m.options.graph = o.at("graph").get<std::string>();
  m.options.graph_checksum = o.at("graph_checksum").get<std::string>();
  m.options.threshold = o.at("threshold").get<std::string>();
  m.options.connectivity = o.at("connectivity").get<int>();
  m.options.moments = o.at("moments").get<bool>();
  m.options.format = o.at("format").get<std::string>();
  for (const json& i : j.at("inputs")) {
    m.inputs.push_back({i.at("path").get<std::string>(), i.at("checksum").get<std::string>(),
                        i.at("bytes").get<std::int64_t>(), i.at("shard").get<std::int64_t>(),
                        i.at("key").get<std::string>()});
  }
  return m;
}

Manifest load_manifest(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw BatchError(fmt::format("manifest {}: cannot read it", path.string()));
  Manifest m;
  try {
    m = manifest_from_json(json::parse(in));
  } catch (const BatchError& e) {
    throw BatchError(fmt::format("manifest {}: {}", path.string(), e.what()));
  } catch (const std::exception& e) {
    throw BatchError(fmt::format("manifest {}: unreadable ({})", path.string(), e.what()));
  }
  if (m.neopipe_version != neopipe::version) {
    throw BatchError(
        fmt::format("manifest {}: made by neopipe {}, this is neopipe {} (tables may differ between "
                    "versions: plan again into a new --out)",
                    path.string(), m.neopipe_version, neopipe::version));
  }
  if (manifest_id(m) != m.id) {
    throw BatchError(
        fmt::format("manifest {}: its content does not match its id {} (edited after planning?)", path.string(), m.id));
  }
  return m;
}

bool write_manifest(const Manifest& m) {
  const fs::path target = m.manifest_path();
  std::error_code ec;
  fs::create_directories(m.out, ec);
  if (ec) throw BatchError(fmt::format("--out {}: cannot create it: {}", m.out, ec.message()));
  if (fs::exists(target)) {
    std::string other_id = "unreadable";
    try {
      std::ifstream in(target);
      other_id = json::parse(in).at("id").get<std::string>();
    } catch (const std::exception&) {
    }
    if (other_id == m.id) return false;
    throw BatchError(
        fmt::format("--out {}: holds another manifest (id {}, this one {}); its tables would mix with "
                    "these: choose another --out, or remove that folder",
                    m.out, other_id, m.id));
  }
  for (const char* sub : {"tables", "done", "failed", "logs"}) fs::create_directories(fs::path(m.out) / sub);
  write_file_atomically(target, manifest_json(m).dump(2) + "\n");
  return true;
}

}  // namespace neopipe::batch
