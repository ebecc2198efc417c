#pragma once
// A declared graph, before validation: nodes (a kernel and its parameters each), the edges feeding
// their inputs (delayed or not) and the graph's outputs. It comes from a YAML file
// (load_graph_spec) or from C++ (GraphBuilder); compile() validates it and makes it runnable.

#include <yaml-cpp/yaml.h>

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pipeline/source_location.hpp"

namespace neopipe::pipeline {

/// "node" (its only output) or "node.port".
struct PortRef {
  std::string node;
  std::string port;  ///< empty: the node's only output
  SourceLocation where;

  std::string str() const { return port.empty() ? node : node + "." + port; }
  /// Parses "node" or "node.port"; throws GraphError at `where` when malformed.
  static PortRef parse(std::string_view text, const SourceLocation& where);
};

/// One input port fed by an edge. A delayed edge (z^-1) delivers what `from` held one frame
/// earlier; on the first frame it delivers `initial`: a constant (every pixel, or every histogram
/// count, set to it; an empty blob table) or another port's value on that same first frame.
struct InputBinding {
  std::string input;  ///< the consumer's input port
  PortRef from;
  bool delayed = false;
  std::variant<int, PortRef> initial = 0;
  SourceLocation where;
};

struct NodeSpec {
  std::string name;
  std::string kernel;
  YAML::Node params;  ///< a map, or null for no parameters
  std::vector<InputBinding> inputs;
  SourceLocation where;         ///< the node's entry
  SourceLocation kernel_where;  ///< its kernel name
};

struct GraphSpec {
  std::string origin;  ///< the file it came from, or a description
  std::string name;
  std::vector<NodeSpec> nodes;
  std::vector<PortRef> outputs;
};

/// Reads a graph spec from a YAML file, checking its structure (not yet its meaning: see compile).
/// Throws GraphError "file:line:column: message".
GraphSpec load_graph_spec(const std::string& path);
/// The same from text; `origin` names it in messages.
GraphSpec parse_graph_spec(const std::string& yaml_text, const std::string& origin);

/// Builds the same GraphSpec in C++:
///   GraphBuilder b("<my graph>");
///   b.node("src", "source").node("bin", "threshold", "{value: otsu}").connect("src", "bin.in");
class GraphBuilder {
 public:
  explicit GraphBuilder(std::string origin = "<c++ graph>");
  /// Adds a node; `params` is a YAML map (or YAML text such as "{value: 128}").
  GraphBuilder& node(const std::string& name, const std::string& kernel, const YAML::Node& params = {});
  GraphBuilder& node(const std::string& name, const std::string& kernel, const std::string& params_yaml);
  /// Feeds input "node.input" from "producer" or "producer.port".
  GraphBuilder& connect(const std::string& from, const std::string& to);
  /// A delayed edge; `initial` is a constant or a port reference (see InputBinding).
  GraphBuilder& connect_delayed(const std::string& from, const std::string& to, int initial);
  GraphBuilder& connect_delayed(const std::string& from, const std::string& to, const std::string& initial_port);
  GraphBuilder& output(const std::string& ref);
  const GraphSpec& spec() const { return spec_; }

 private:
  NodeSpec& consumer(const std::string& to, std::string& input);
  GraphSpec spec_;
};

}  // namespace neopipe::pipeline
