#include "pipeline/threshold_folding.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>

namespace neopipe::pipeline {
namespace {

/// An integer parameter, or nullopt when it is absent (use `fallback`) or not a number ("otsu").
std::optional<int> int_param(const YAML::Node& params, const char* key, std::optional<int> fallback) {
  if (!params.IsMap() || !params[key]) return fallback;
  try {
    return params[key].as<int>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

bool reads(const InputBinding& b, const std::string& node) {
  return b.from.node == node ||
         (std::holds_alternative<PortRef>(b.initial) && std::get<PortRef>(b.initial).node == node);
}

const InputBinding* binding(const NodeSpec& n, const std::string& input) {
  const auto it =
      std::find_if(n.inputs.begin(), n.inputs.end(), [&](const InputBinding& b) { return b.input == input; });
  return it == n.inputs.end() ? nullptr : &*it;
}

/// The index of the blobs node `threshold` folds into, if it does.
std::optional<size_t> fold_target(const GraphSpec& spec, const NodeSpec& threshold) {
  if (threshold.kernel != "threshold") return std::nullopt;
  const auto high = int_param(threshold.params, "high", 255);
  const InputBinding* source = binding(threshold, "in");
  if (!high || source == nullptr || source->delayed) return std::nullopt;
  if (std::any_of(spec.outputs.begin(), spec.outputs.end(), [&](const PortRef& o) { return o.node == threshold.name; }))
    return std::nullopt;
  std::optional<size_t> target;
  int readers = 0;
  for (size_t i = 0; i < spec.nodes.size(); ++i) {
    for (const auto& b : spec.nodes[i].inputs) {
      if (!reads(b, threshold.name)) continue;
      ++readers;
      if (spec.nodes[i].kernel == "blobs" && b.input == "in" && !b.delayed && b.from.node == threshold.name) target = i;
    }
  }
  if (readers != 1 || !target) return std::nullopt;
  const NodeSpec& blobs = spec.nodes[*target];
  const auto t = int_param(blobs.params, "threshold", 0);
  if (!t || *t < 0 || *t >= *high || binding(blobs, "weights") == nullptr) return std::nullopt;
  return target;
}

// yaml-cpp's Node::operator= writes through to every handle of the node, so a spec is never
// assigned to or erased from (that would rewrite the caller's spec): each fold builds a new one.
GraphSpec fold_one(const GraphSpec& spec, size_t threshold_index, size_t blobs_index) {
  const NodeSpec& threshold = spec.nodes[threshold_index];
  std::vector<NodeSpec> nodes;
  for (size_t i = 0; i < spec.nodes.size(); ++i) {
    if (i == threshold_index) continue;
    const NodeSpec& n = spec.nodes[i];
    if (i != blobs_index) {
      nodes.push_back(n);
      continue;
    }
    YAML::Node params = n.params.IsMap() ? YAML::Clone(n.params) : YAML::Node(YAML::NodeType::Map);
    // A fixed value, or Otsu's: blobs chooses it from the histogram of its own `in`, which is now
    // the threshold's input, so it is the same T.
    if (const auto value = int_param(threshold.params, "value", std::nullopt)) {
      params["threshold"] = *value;
    } else {
      params["threshold"] = "otsu";
    }
    std::vector<InputBinding> inputs = n.inputs;
    for (auto& b : inputs) {
      if (b.input == "in") b.from = binding(threshold, "in")->from;
    }
    nodes.push_back(NodeSpec{n.name, n.kernel, params, std::move(inputs), n.where, n.kernel_where});
  }
  return GraphSpec{spec.origin, spec.name, std::move(nodes), spec.outputs};
}

}  // namespace

std::optional<GraphSpec> fold_thresholds_into_blobs(const GraphSpec& spec) {
  std::optional<GraphSpec> folded;
  for (;;) {
    const GraphSpec& current = folded ? *folded : spec;
    std::optional<GraphSpec> next;
    for (size_t i = 0; i < current.nodes.size() && !next; ++i) {
      if (const auto target = fold_target(current, current.nodes[i])) next.emplace(fold_one(current, i, *target));
    }
    if (!next) return folded;
    folded.emplace(std::move(*next));
  }
}

}  // namespace neopipe::pipeline
