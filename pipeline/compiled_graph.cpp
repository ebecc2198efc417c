#include "pipeline/compiled_graph.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "pipeline/nodes/nodes.hpp"
#include "pipeline/threshold_folding.hpp"

namespace neopipe::pipeline {
namespace {

std::string join_port_names(const std::vector<PortDecl>& ports) {
  std::string s;
  for (const auto& p : ports) s += (s.empty() ? "" : ", ") + p.name;
  return s.empty() ? "none" : s;
}

struct Resolver {
  const GraphSpec& spec;
  const std::vector<std::unique_ptr<Node>>& impls;
  std::map<std::string, int> index;

  PortAddress resolve(const PortRef& ref) const {
    const auto it = index.find(ref.node);
    if (it == index.end()) throw GraphError(ref.where, "no node named '" + ref.node + "'");
    const auto& outs = impls[static_cast<size_t>(it->second)]->outputs();
    if (ref.port.empty()) {
      if (outs.size() != 1) {
        throw GraphError(ref.where, "node '" + ref.node + "' has " + std::to_string(outs.size()) +
                                        " outputs; name one: " + join_port_names(outs));
      }
      return {it->second, 0};
    }
    for (size_t k = 0; k < outs.size(); ++k) {
      if (outs[k].name == ref.port) return {it->second, static_cast<int>(k)};
    }
    throw GraphError(
        ref.where, "node '" + ref.node + "' has no output '" + ref.port + "' (outputs: " + join_port_names(outs) + ")");
  }

  PortType type(PortAddress a) const {
    return impls[static_cast<size_t>(a.node)]->outputs()[static_cast<size_t>(a.port)].type;
  }
};

// The constants a delayed input of this type can start from.
std::pair<int, int> fill_range(PortType t) {
  switch (t) {
    case PortType::s16:
      return {-32768, 32767};
    case PortType::histogram:
      return {0, std::numeric_limits<int>::max()};
    default:
      return {0, 255};
  }
}

// One dependency edge of the first frame: consumer waits for producer (non-delayed inputs and
// delayed inputs' initial ports). A cycle among these is an error.
struct Dependency {
  int producer;
  int consumer;
  SourceLocation where;
};

[[noreturn]] void report_cycle(const GraphSpec& spec, const std::vector<Dependency>& deps,
                               const std::vector<int>& left) {
  // Walk backwards from any node left over by the topological sort: each has a producer that is
  // also left over, so the walk must revisit a node, and the revisited stretch is a cycle.
  const std::set<int> remaining(left.begin(), left.end());
  std::vector<int> path{left.front()};
  std::vector<const Dependency*> via;
  for (;;) {
    const int cur = path.back();
    const auto it = std::find_if(deps.begin(), deps.end(), [&](const Dependency& d) {
      return d.consumer == cur && remaining.count(d.producer) != 0;
    });
    const auto seen = std::find(path.begin(), path.end(), it->producer);
    via.push_back(&*it);
    if (seen != path.end()) {
      // path[k + 1] feeds path[k], so reading the path backwards follows the data.
      const auto start = static_cast<size_t>(seen - path.begin());
      std::string text;
      for (size_t i = path.size(); i-- > start;) text += spec.nodes[static_cast<size_t>(path[i])].name + " -> ";
      text += spec.nodes[static_cast<size_t>(path.back())].name;
      throw GraphError(via.back()->where, "cycle without a delay: " + text +
                                              " (a cycle is legal only through an input marked 'delay: 1')");
    }
    path.push_back(it->producer);
  }
}

}  // namespace

PortType CompiledGraph::type_of(PortAddress a) const {
  return nodes_[static_cast<size_t>(a.node)].impl->outputs()[static_cast<size_t>(a.port)].type;
}

std::optional<size_t> CompiledGraph::find_output(PortType t) const {
  for (size_t i = 0; i < outputs_.size(); ++i) {
    if (type_of(outputs_[i]) == t) return i;
  }
  return std::nullopt;
}

CompiledGraph compile_as_declared(const GraphSpec& spec, const KernelRegistry& registry) {
  const SourceLocation graph_where{spec.origin, 0, 0};
  if (spec.nodes.empty()) throw GraphError(graph_where, "the graph has no nodes");

  // 1. Make every node from its kernel and parameters.
  std::vector<std::unique_ptr<Node>> impls;
  Resolver r{spec, impls, {}};
  const std::filesystem::path base_dir = std::filesystem::path(spec.origin).parent_path();
  int source = -1;
  for (const auto& n : spec.nodes) {
    if (!r.index.emplace(n.name, static_cast<int>(impls.size())).second) {
      throw GraphError(n.where, "duplicate node name '" + n.name + "'");
    }
    const KernelInfo* k = registry.find(n.kernel);
    if (k == nullptr) {
      std::string known;
      for (const auto* info : registry.all()) known += (known.empty() ? "" : ", ") + info->name;
      throw GraphError(n.kernel_where, "unknown kernel '" + n.kernel + "' (known: " + known + ")");
    }
    ParamReader params(n.params, n.kernel_where, n.kernel);
    NodeContext ctx{n.name, params, n.where, base_dir};
    impls.push_back(k->make(ctx));
    params.finish();
    if (n.kernel == nodes::kSourceKernel) {
      if (source >= 0)
        throw GraphError(n.where, "a graph has one 'source' node; '" + spec.nodes[static_cast<size_t>(source)].name +
                                      "' is already one");
      source = static_cast<int>(impls.size()) - 1;
    }
  }
  if (source < 0) throw GraphError(graph_where, "the graph has no node of kernel 'source' (the frames it processes)");

  // 2. Resolve and type-check every input.
  std::vector<std::vector<CompiledInput>> inputs(spec.nodes.size());
  std::vector<Dependency> deps;
  std::set<std::pair<int, int>> consumed;
  bool has_delays = false;
  for (size_t i = 0; i < spec.nodes.size(); ++i) {
    const NodeSpec& n = spec.nodes[i];
    const auto& decls = impls[i]->inputs();
    inputs[i].resize(decls.size());
    std::vector<bool> bound(decls.size(), false);
    for (const auto& b : n.inputs) {
      const auto d = std::find_if(decls.begin(), decls.end(), [&](const PortDecl& p) { return p.name == b.input; });
      if (d == decls.end()) {
        throw GraphError(b.where, "node '" + n.name + "' (" + n.kernel + ") has no input '" + b.input +
                                      "' (inputs: " + join_port_names(decls) + ")");
      }
      const auto k = static_cast<size_t>(d - decls.begin());
      bound[k] = true;
      CompiledInput& in = inputs[i][k];
      in.from = r.resolve(b.from);
      const PortType t = r.type(in.from);
      if (t != d->type) {
        throw GraphError(b.from.where, "type mismatch: input '" + b.input + "' of node '" + n.name + "' takes " +
                                           std::string(to_string(d->type)) + " but '" + b.from.str() + "' is " +
                                           std::string(to_string(t)));
      }
      consumed.emplace(in.from.node, in.from.port);
      in.delayed = b.delayed;
      if (b.delayed) {
        has_delays = true;
        if (const auto* fill = std::get_if<int>(&b.initial)) {
          const auto [lo, hi] = fill_range(d->type);
          if (*fill < lo || *fill > hi) {
            throw GraphError(b.where, "the initial value of input '" + b.input + "' of node '" + n.name + "' is " +
                                          std::to_string(*fill) + ", outside the " + std::string(to_string(d->type)) +
                                          " range " + std::to_string(lo) + ".." + std::to_string(hi));
          }
          in.initial_fill = *fill;
        } else {
          const auto& init = std::get<PortRef>(b.initial);
          in.initial_from = r.resolve(init);
          const PortType it = r.type(in.initial_from);
          if (it != d->type) {
            throw GraphError(init.where, "type mismatch: the initial value of input '" + b.input + "' of node '" +
                                             n.name + "' must be " + std::string(to_string(d->type)) + " but '" +
                                             init.str() + "' is " + std::string(to_string(it)));
          }
          deps.push_back({in.initial_from.node, static_cast<int>(i), init.where});
          consumed.emplace(in.initial_from.node, in.initial_from.port);
        }
      } else {
        deps.push_back({in.from.node, static_cast<int>(i), b.from.where});
      }
    }
    for (size_t k = 0; k < decls.size(); ++k) {
      if (!bound[k] && !decls[k].optional) {
        throw GraphError(n.where,
                         "input '" + decls[k].name + "' of node '" + n.name + "' (" + n.kernel + ") is not connected");
      }
    }
  }

  // 3. Outputs, and no output port that goes nowhere.
  CompiledGraph g;
  g.origin_ = spec.origin;
  g.has_delays_ = has_delays;
  if (spec.outputs.empty()) throw GraphError(graph_where, "the graph declares no outputs");
  std::vector<PortAddress> outputs;
  for (const auto& o : spec.outputs) {
    outputs.push_back(r.resolve(o));
    consumed.emplace(outputs.back().node, outputs.back().port);
    g.output_names_.push_back(o.str());
  }
  for (size_t i = 0; i < spec.nodes.size(); ++i) {
    const auto& outs = impls[i]->outputs();
    for (size_t k = 0; k < outs.size(); ++k) {
      if (consumed.count({static_cast<int>(i), static_cast<int>(k)}) == 0) {
        throw GraphError(spec.nodes[i].where, "dangling port: output '" + outs[k].name + "' of node '" +
                                                  spec.nodes[i].name +
                                                  "' goes nowhere (connect it or list it under outputs)");
      }
    }
  }

  // 4. Order the nodes so that every first-frame dependency comes first; the smallest declared index
  // goes first among the ready ones, so the order is stable.
  const size_t n = spec.nodes.size();
  std::vector<int> indegree(n, 0);
  for (const auto& d : deps) ++indegree[static_cast<size_t>(d.consumer)];
  std::set<int> ready;
  for (size_t i = 0; i < n; ++i) {
    if (indegree[i] == 0) ready.insert(static_cast<int>(i));
  }
  std::vector<int> order;
  while (!ready.empty()) {
    const int cur = *ready.begin();
    ready.erase(ready.begin());
    order.push_back(cur);
    for (const auto& d : deps) {
      if (d.producer == cur && --indegree[static_cast<size_t>(d.consumer)] == 0) ready.insert(d.consumer);
    }
  }
  if (order.size() != n) {
    std::vector<int> left;
    for (size_t i = 0; i < n; ++i) {
      if (indegree[i] > 0) left.push_back(static_cast<int>(i));
    }
    report_cycle(spec, deps, left);
  }

  // 5. Renumber into that order.
  std::vector<int> new_index(n);
  for (size_t k = 0; k < n; ++k) new_index[static_cast<size_t>(order[k])] = static_cast<int>(k);
  const auto renumber = [&](PortAddress a) {
    return a.valid() ? PortAddress{new_index[static_cast<size_t>(a.node)], a.port} : a;
  };
  for (const int old : order) {
    const auto o = static_cast<size_t>(old);
    CompiledNode cn{spec.nodes[o].name, spec.nodes[o].kernel, std::move(impls[o]), std::move(inputs[o]),
                    spec.nodes[o].where};
    for (auto& in : cn.inputs) {
      in.from = renumber(in.from);
      in.initial_from = renumber(in.initial_from);
    }
    g.nodes_.push_back(std::move(cn));
  }
  g.source_ = new_index[static_cast<size_t>(source)];
  for (const auto& o : outputs) g.outputs_.push_back(renumber(o));
  return g;
}

CompiledGraph compile(const GraphSpec& spec, const KernelRegistry& registry, const CompileOptions& options) {
  // Validated as declared first, so that every message speaks of the graph the user wrote and a
  // mistake in a node the fold removes (a threshold's bad `high`) is still reported.
  CompiledGraph g = compile_as_declared(spec, registry);
  if (!options.fold_thresholds) return g;
  if (auto folded = fold_thresholds_into_blobs(spec)) return compile_as_declared(*folded, registry);
  return g;
}

}  // namespace neopipe::pipeline
