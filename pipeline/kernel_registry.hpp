#pragma once
// The kernels a graph spec can name: each entry makes a configured Node from its parameters.
// A registry is an ordinary object (no global table), so tests and applications can extend theirs.

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/node.hpp"
#include "pipeline/params.hpp"

namespace neopipe::pipeline {

struct NodeContext {
  std::string name;                ///< the node's name in the graph
  ParamReader& params;             ///< its parameters
  SourceLocation where;            ///< where it is declared
  std::filesystem::path base_dir;  ///< the spec's directory, for relative file parameters
};

struct KernelInfo {
  std::string name;
  std::string summary;  ///< one line for `neopipe run --list-kernels`
  std::function<std::unique_ptr<Node>(NodeContext&)> make;
};

class KernelRegistry {
 public:
  void add(KernelInfo info);
  /// Pointers into the registry: it must outlive them, so a temporary registry cannot hand them out
  /// (`for (auto* k : standard_kernels().all())` read freed memory: a compile error now).
  const KernelInfo* find(std::string_view name) const&;
  const KernelInfo* find(std::string_view name) const&& = delete;
  std::vector<const KernelInfo*> all() const&;
  std::vector<const KernelInfo*> all() const&& = delete;

 private:
  std::map<std::string, KernelInfo, std::less<>> kernels_;
};

/// source, image, gray, lut, threshold, add, sub, absdiff, min, max, and, or, xor, lut2, conv3x3,
/// bool3x3, convert, histogram, blobs, value_blobs.
KernelRegistry standard_kernels();

}  // namespace neopipe::pipeline
