#include "pipeline/graph_spec.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

namespace neopipe::pipeline {
namespace {

bool is_identifier(std::string_view s) {
  if (s.empty() || (std::isalpha(static_cast<unsigned char>(s[0])) == 0 && s[0] != '_')) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-'; });
}

SourceLocation at(const std::string& file, const YAML::Mark& m) {
  if (m.is_null() || m.line < 0) return {file, 0, 0};
  return {file, m.line + 1, m.column + 1};
}

class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  GraphSpec read(const YAML::Node& root) {
    GraphSpec g;
    g.origin = origin_;
    if (!root.IsMap()) fail(root, "a graph spec is a map with 'nodes' and 'outputs'");
    for (const auto& kv : root) {
      const std::string key = key_of(kv.first);
      if (key != "name" && key != "description" && key != "nodes" && key != "outputs") {
        fail(kv.first, "unknown key '" + key + "' (expected name, description, nodes, outputs)");
      }
    }
    if (root["name"]) g.name = scalar(root["name"], "name");
    const YAML::Node nodes = root["nodes"];
    if (!nodes) fail(root, "missing 'nodes'");
    if (!nodes.IsSequence() || nodes.size() == 0) fail(nodes, "'nodes' must be a non-empty list");
    std::set<std::string> names;
    for (const auto& n : nodes) {
      g.nodes.push_back(read_node(n));
      if (!names.insert(g.nodes.back().name).second) {
        fail(n["name"], "duplicate node name '" + g.nodes.back().name + "'");
      }
    }
    const YAML::Node outputs = root["outputs"];
    if (!outputs) fail(root, "missing 'outputs' (the ports whose values leave the graph)");
    if (outputs.IsScalar()) {
      g.outputs.push_back(PortRef::parse(outputs.Scalar(), where(outputs)));
    } else if (outputs.IsSequence() && outputs.size() > 0) {
      for (const auto& o : outputs) g.outputs.push_back(PortRef::parse(scalar(o, "output"), where(o)));
    } else {
      fail(outputs, "'outputs' must be a port reference or a non-empty list of them");
    }
    return g;
  }

 private:
  NodeSpec read_node(const YAML::Node& n) {
    if (!n.IsMap()) fail(n, "a node is a map with 'name' and 'kernel'");
    NodeSpec spec;
    spec.where = where(n);
    for (const auto& kv : n) {
      const std::string key = key_of(kv.first);
      if (key != "name" && key != "kernel" && key != "params" && key != "inputs") {
        fail(kv.first, "unknown key '" + key + "' in a node (expected name, kernel, params, inputs)");
      }
    }
    if (!n["name"]) fail(n, "node without a 'name'");
    spec.name = scalar(n["name"], "node name");
    if (!is_identifier(spec.name)) {
      fail(n["name"], "node name '" + spec.name + "' must be letters, digits, '_' or '-', not starting with a digit");
    }
    if (!n["kernel"]) fail(n, "node '" + spec.name + "' has no 'kernel'");
    spec.kernel = scalar(n["kernel"], "kernel");
    spec.kernel_where = where(n["kernel"]);
    if (const YAML::Node p = n["params"]) {
      if (!p.IsMap() && !p.IsNull()) fail(p, "'params' must be a map of name: value");
      spec.params = p;
    }
    if (const YAML::Node in = n["inputs"]) {
      if (!in.IsMap()) fail(in, "'inputs' must be a map of input: source");
      std::set<std::string> seen;
      for (const auto& kv : in) {
        InputBinding b;
        b.input = scalar(kv.first, "input name");
        b.where = where(kv.first);
        if (!seen.insert(b.input).second) fail(kv.first, "input '" + b.input + "' is given twice");
        read_binding(kv.second, b);
        spec.inputs.push_back(std::move(b));
      }
    }
    return spec;
  }

  void read_binding(const YAML::Node& v, InputBinding& b) {
    if (v.IsScalar()) {
      b.from = PortRef::parse(v.Scalar(), where(v));
      return;
    }
    if (!v.IsMap()) fail(v, "an input is a port (\"node\" or \"node.port\") or a map {from, delay, initial}");
    for (const auto& kv : v) {
      const std::string key = key_of(kv.first);
      if (key != "from" && key != "delay" && key != "initial") {
        fail(kv.first, "unknown key '" + key + "' in an input (expected from, delay, initial)");
      }
    }
    if (!v["from"]) fail(v, "input '" + b.input + "' has no 'from'");
    b.from = PortRef::parse(scalar(v["from"], "from"), where(v["from"]));
    if (const YAML::Node d = v["delay"]) {
      const std::string text = scalar(d, "delay");
      if (text != "1" && text != "0") fail(d, "'delay' must be 1 (one frame, z^-1) or 0");
      b.delayed = text == "1";
    }
    if (const YAML::Node init = v["initial"]) {
      if (!b.delayed) fail(init, "'initial' only applies to a delayed input (delay: 1)");
      const std::string text = scalar(init, "initial");
      int value = 0;
      std::istringstream is(text);
      if (is >> value && is.eof()) {
        b.initial = value;
      } else {
        b.initial = PortRef::parse(text, where(init));
      }
    }
  }

  // A map key as text. YAML allows any node as a key ("[a, b]: 1", "? {a: 1}"), and yaml-cpp's
  // as<std::string>() throws its own exception for those, which would escape as a crash instead of
  // a GraphError (found by fuzz/fuzz_graph_spec.cpp).
  std::string key_of(const YAML::Node& key) const {
    if (!key.IsScalar()) fail(key, "a key must be a single name");
    return key.Scalar();
  }

  std::string scalar(const YAML::Node& n, const std::string& what) {
    if (!n.IsScalar()) fail(n, what + " must be a single value");
    return n.Scalar();
  }

  SourceLocation where(const YAML::Node& n) const { return at(origin_, n.Mark()); }
  [[noreturn]] void fail(const YAML::Node& n, const std::string& msg) const { throw GraphError(where(n), msg); }

  std::string origin_;
};

}  // namespace

PortRef PortRef::parse(std::string_view text, const SourceLocation& where) {
  PortRef r;
  r.where = where;
  const auto dot = text.find('.');
  r.node = std::string(text.substr(0, dot));
  if (dot != std::string_view::npos) r.port = std::string(text.substr(dot + 1));
  if (!is_identifier(r.node) || (dot != std::string_view::npos && !is_identifier(r.port))) {
    throw GraphError(where, "bad port reference '" + std::string(text) + "' (expected node or node.port)");
  }
  return r;
}

GraphSpec parse_graph_spec(const std::string& yaml_text, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw GraphError(at(origin, e.mark), e.msg);
  }
  return Reader(origin).read(root);
}

GraphSpec load_graph_spec(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GraphError({path, 0, 0}, "cannot open the graph spec");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_graph_spec(text.str(), path);
}

GraphBuilder::GraphBuilder(std::string origin) {
  spec_.origin = std::move(origin);
}

GraphBuilder& GraphBuilder::node(const std::string& name, const std::string& kernel, const YAML::Node& params) {
  NodeSpec n;
  n.name = name;
  n.kernel = kernel;
  n.params = params;
  n.where = {spec_.origin, 0, 0};
  n.kernel_where = n.where;
  spec_.nodes.push_back(std::move(n));
  return *this;
}

GraphBuilder& GraphBuilder::node(const std::string& name, const std::string& kernel, const std::string& params_yaml) {
  return node(name, kernel, YAML::Load(params_yaml));
}

NodeSpec& GraphBuilder::consumer(const std::string& to, std::string& input) {
  const SourceLocation where{spec_.origin, 0, 0};
  const PortRef ref = PortRef::parse(to, where);
  if (ref.port.empty()) throw GraphError(where, "connect(): the target must be node.input, got '" + to + "'");
  const auto it =
      std::find_if(spec_.nodes.begin(), spec_.nodes.end(), [&](const NodeSpec& n) { return n.name == ref.node; });
  if (it == spec_.nodes.end()) throw GraphError(where, "connect(): no node named '" + ref.node + "'");
  input = ref.port;
  return *it;
}

GraphBuilder& GraphBuilder::connect(const std::string& from, const std::string& to) {
  InputBinding b;
  NodeSpec& n = consumer(to, b.input);
  b.from = PortRef::parse(from, {spec_.origin, 0, 0});
  b.where = {spec_.origin, 0, 0};
  n.inputs.push_back(std::move(b));
  return *this;
}

GraphBuilder& GraphBuilder::connect_delayed(const std::string& from, const std::string& to, int initial) {
  connect(from, to);
  std::string input;
  NodeSpec& n = consumer(to, input);
  n.inputs.back().delayed = true;
  n.inputs.back().initial = initial;
  return *this;
}

GraphBuilder& GraphBuilder::connect_delayed(const std::string& from, const std::string& to,
                                            const std::string& initial_port) {
  connect_delayed(from, to, 0);
  std::string input;
  consumer(to, input).inputs.back().initial = PortRef::parse(initial_port, {spec_.origin, 0, 0});
  return *this;
}

GraphBuilder& GraphBuilder::output(const std::string& ref) {
  spec_.outputs.push_back(PortRef::parse(ref, {spec_.origin, 0, 0}));
  return *this;
}

}  // namespace neopipe::pipeline
