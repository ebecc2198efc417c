#pragma once
// A validated graph, ready to run: nodes configured and in an order where every non-delayed producer
// comes before its consumers, every input resolved to a producer port of the right type.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/node.hpp"

namespace neopipe::pipeline {

struct PortAddress {
  int node = -1;  ///< index into CompiledGraph::nodes(); -1 when unconnected
  int port = -1;
  bool valid() const { return node >= 0; }
  bool operator==(const PortAddress&) const = default;
};

struct CompiledInput {
  PortAddress from;          ///< invalid for an unconnected optional input
  bool delayed = false;      ///< reads `from` as it was one frame earlier
  int initial_fill = 0;      ///< delayed, first frame: a constant ...
  PortAddress initial_from;  ///< ... or, when valid, this port's value on the first frame
};

struct CompiledNode {
  std::string name;
  std::string kernel;
  std::unique_ptr<Node> impl;
  std::vector<CompiledInput> inputs;  ///< one per declared input port
  SourceLocation where;
};

class CompiledGraph {
 public:
  const std::string& origin() const { return origin_; }
  const std::vector<CompiledNode>& nodes() const { return nodes_; }
  std::vector<CompiledNode>& nodes() { return nodes_; }
  /// The frame source node and the type of frame it takes (bgr8 or gray8).
  int source() const { return source_; }
  PortType source_type() const { return nodes_[static_cast<size_t>(source_)].impl->outputs()[0].type; }
  const std::vector<PortAddress>& outputs() const { return outputs_; }
  const std::vector<std::string>& output_names() const { return output_names_; }
  PortType type_of(PortAddress a) const;
  bool has_delays() const { return has_delays_; }
  /// Index of the first output of type t, if any.
  std::optional<size_t> find_output(PortType t) const;

 private:
  friend CompiledGraph compile_as_declared(const GraphSpec& spec, const KernelRegistry& registry);
  std::string origin_;
  std::vector<CompiledNode> nodes_;
  int source_ = -1;
  std::vector<PortAddress> outputs_;
  std::vector<std::string> output_names_;
  bool has_delays_ = false;
};

struct CompileOptions {
  /// Fold fixed thresholds into the blob nodes that alone read them (see threshold_folding.hpp):
  /// same blob tables, one pass over the frame instead of three.
  bool fold_thresholds = true;
};

/// Validates the spec and configures its nodes. Throws GraphError ("file:line:column: message") on
/// an unknown kernel or parameter, a bad parameter value, an unknown node or port, a type mismatch,
/// an unconnected input, an output that goes nowhere (dangling), or a cycle without a delay.
CompiledGraph compile(const GraphSpec& spec, const KernelRegistry& registry, const CompileOptions& options = {});

/// compile() without the optimising passes: the nodes exactly as declared.
CompiledGraph compile_as_declared(const GraphSpec& spec, const KernelRegistry& registry);

}  // namespace neopipe::pipeline
