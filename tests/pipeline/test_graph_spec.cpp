// Tests of reading graph specs (pipeline/graph_spec.hpp). Valid YAML specs come back as the
// expected GraphSpec: inputs in string and map form, delayed inputs with an integer or a port as
// initial value, outputs as one scalar or a list, and every node, kernel and input carrying its
// line:column. Every structural mistake is a GraphError whose what() is exactly
// "origin:line:column: message", pointing at the offending key or value (YAML syntax errors,
// unknown keys, missing or empty nodes/outputs, nameless or kernel-less nodes, bad or duplicate
// names, bad delays, 'initial' without a delay, malformed port references). Finally, a graph built
// with GraphBuilder in C++ is the same spec as its YAML twin: same structure, and identical results
// frame by frame when both are compiled and run.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)

namespace {

const char* const kOrigin = "spec.yaml";

// Parses `yaml`, which must fail, and returns the GraphError's what().
std::string spec_error(const std::string& yaml) {
  try {
    (void)pl::parse_graph_spec(yaml, kOrigin);
  } catch (const pl::GraphError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a GraphError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "the spec was accepted:\n" << yaml;
  return {};
}

void expect_location(const pl::SourceLocation& where, int line, int column) {
  EXPECT_EQ(where.file, kOrigin);
  EXPECT_EQ(where.line, line);
  EXPECT_EQ(where.column, column);
}

const pl::InputBinding& input_named(const pl::NodeSpec& n, const std::string& input) {
  for (const auto& b : n.inputs) {
    if (b.input == input) return b;
  }
  throw std::runtime_error("node '" + n.name + "' has no binding for input '" + input + "'");
}

std::vector<cv::Mat> random_gray_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, CV_8UC1);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    frames.push_back(f);
  }
  return frames;
}

// Runs both specs on the same frames and requires identical image outputs.
void expect_same_results(const pl::GraphSpec& a, const pl::GraphSpec& b, const std::vector<cv::Mat>& frames) {
  const auto ra = pl::run_frames(pl::compile(a, pl::standard_kernels()), frames, {.threads = 2});
  const auto rb = pl::run_frames(pl::compile(b, pl::standard_kernels()), frames, {.threads = 2});
  ASSERT_EQ(ra.size(), frames.size());
  ASSERT_EQ(rb.size(), frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    ASSERT_EQ(ra[f].outputs.size(), rb[f].outputs.size());
    for (size_t o = 0; o < ra[f].outputs.size(); ++o) {
      const auto& ma = std::get<cv::Mat>(ra[f].outputs[o]);
      const auto& mb = std::get<cv::Mat>(rb[f].outputs[o]);
      ASSERT_EQ(ma.size(), mb.size());
      ASSERT_EQ(ma.type(), mb.type());
      EXPECT_EQ(cv::norm(ma, mb, cv::NORM_INF), 0) << "frame " << f << ", output " << o;
    }
  }
}

// A running average (a delay edge with a constant initial value, feeding a node its own output) and
// a frame difference (a delay edge whose initial value is another port), as YAML.
const std::string kDelayGraphYaml = yaml_lines({
    /* 1 */ "name: delays",
    /* 2 */ "description: running average and frame difference",
    /* 3 */ "nodes:",
    /* 4 */ "  - name: src",
    /* 5 */ "    kernel: source",
    /* 6 */ "    params: {format: gray}",
    /* 7 */ "  - name: avg",
    /* 8 */ "    kernel: lut2",
    /* 9 */ "    params: {expr: \"floor((a + 3*b) / 4)\"}",
    /*10 */ "    inputs:",
    /*11 */ "      a: src",
    /*12 */ "      b: {from: avg, delay: 1, initial: 7}",
    /*13 */ "  - name: diff",
    /*14 */ "    kernel: absdiff",
    /*15 */ "    inputs:",
    /*16 */ "      a: {from: src}",
    /*17 */ "      b: {from: src.out, delay: 1, initial: src}",
    /*18 */ "outputs: [avg, diff.out]",
});

}  // namespace

// ---------------------------------------------------------------------------------------------
// Valid specs

TEST(GraphSpecYaml, ReadsNodesInputsAndOutputs) {
  const pl::GraphSpec g = pl::parse_graph_spec(kDelayGraphYaml, kOrigin);
  EXPECT_EQ(g.origin, kOrigin);
  EXPECT_EQ(g.name, "delays");
  ASSERT_EQ(g.nodes.size(), 3U);

  const pl::NodeSpec& src = g.nodes[0];
  EXPECT_EQ(src.name, "src");
  EXPECT_EQ(src.kernel, "source");
  expect_location(src.where, 4, 5);          // the node's map starts at "name"
  expect_location(src.kernel_where, 5, 13);  // "source"
  ASSERT_TRUE(src.params.IsMap());
  EXPECT_EQ(src.params["format"].as<std::string>(), "gray");
  EXPECT_TRUE(src.inputs.empty());

  const pl::NodeSpec& avg = g.nodes[1];
  EXPECT_EQ(avg.kernel, "lut2");
  EXPECT_EQ(avg.params["expr"].as<std::string>(), "floor((a + 3*b) / 4)");
  ASSERT_EQ(avg.inputs.size(), 2U);
  const pl::InputBinding& a = input_named(avg, "a");  // string form
  EXPECT_EQ(a.from.node, "src");
  EXPECT_EQ(a.from.port, "");
  EXPECT_FALSE(a.delayed);
  expect_location(a.where, 11, 7);
  expect_location(a.from.where, 11, 10);
  const pl::InputBinding& b = input_named(avg, "b");  // map form, integer initial value
  EXPECT_EQ(b.from.str(), "avg");
  EXPECT_TRUE(b.delayed);
  ASSERT_TRUE(std::holds_alternative<int>(b.initial));
  EXPECT_EQ(std::get<int>(b.initial), 7);
  expect_location(b.where, 12, 7);
  expect_location(b.from.where, 12, 17);

  const pl::NodeSpec& diff = g.nodes[2];
  const pl::InputBinding& da = input_named(diff, "a");  // map form without delay
  EXPECT_EQ(da.from.str(), "src");
  EXPECT_FALSE(da.delayed);
  const pl::InputBinding& db = input_named(diff, "b");  // explicit port, port as initial value
  EXPECT_EQ(db.from.node, "src");
  EXPECT_EQ(db.from.port, "out");
  EXPECT_EQ(db.from.str(), "src.out");
  EXPECT_TRUE(db.delayed);
  ASSERT_TRUE(std::holds_alternative<pl::PortRef>(db.initial));
  EXPECT_EQ(std::get<pl::PortRef>(db.initial).str(), "src");
  expect_location(std::get<pl::PortRef>(db.initial).where, 17, 45);

  ASSERT_EQ(g.outputs.size(), 2U);  // list form
  EXPECT_EQ(g.outputs[0].str(), "avg");
  EXPECT_EQ(g.outputs[1].node, "diff");
  EXPECT_EQ(g.outputs[1].port, "out");
  expect_location(g.outputs[0].where, 18, 11);
  expect_location(g.outputs[1].where, 18, 16);
}

TEST(GraphSpecYaml, ScalarOutputFlowNodesAndOptionalKeys) {
  const pl::GraphSpec g = pl::parse_graph_spec(yaml_lines({
                                                   /* 1 */ "nodes:",
                                                   /* 2 */ "  - {name: src, kernel: source}",
                                                   /* 3 */ "  - name: my-gray_2",
                                                   /* 4 */ "    kernel: gray",
                                                   /* 5 */ "    params:",
                                                   /* 6 */ "    inputs: {in: {from: src, delay: 0}}",
                                                   /* 7 */ "outputs: my-gray_2",
                                               }),
                                               kOrigin);
  EXPECT_EQ(g.name, "");
  ASSERT_EQ(g.nodes.size(), 2U);
  expect_location(g.nodes[0].where, 2, 5);  // a flow map starts at its '{'
  expect_location(g.nodes[0].kernel_where, 2, 25);
  EXPECT_TRUE(g.nodes[0].params.IsNull());  // no params key
  EXPECT_EQ(g.nodes[1].name, "my-gray_2");
  EXPECT_TRUE(g.nodes[1].params.IsNull());  // "params:" with nothing is no parameters
  ASSERT_EQ(g.nodes[1].inputs.size(), 1U);
  EXPECT_FALSE(g.nodes[1].inputs[0].delayed);  // delay: 0 is an ordinary edge
  ASSERT_EQ(g.outputs.size(), 1U);             // scalar form
  EXPECT_EQ(g.outputs[0].str(), "my-gray_2");
  expect_location(g.outputs[0].where, 7, 10);
}

TEST(GraphSpecYaml, DelayWithoutInitialStartsFromZero) {
  const pl::GraphSpec g = pl::parse_graph_spec(yaml_lines({
                                                   "nodes:",
                                                   "  - {name: src, kernel: source, params: {format: gray}}",
                                                   "  - name: d",
                                                   "    kernel: absdiff",
                                                   "    inputs: {a: src, b: {from: src, delay: 1}}",
                                                   "outputs: d",
                                               }),
                                               kOrigin);
  const pl::InputBinding& b = input_named(g.nodes[1], "b");
  EXPECT_TRUE(b.delayed);
  ASSERT_TRUE(std::holds_alternative<int>(b.initial));
  EXPECT_EQ(std::get<int>(b.initial), 0);
}

TEST(GraphSpecYaml, NegativeIntegerInitialIsAConstant) {
  const pl::GraphSpec g = pl::parse_graph_spec(yaml_lines({
                                                   "nodes:",
                                                   "  - {name: src, kernel: source, params: {format: gray}}",
                                                   "  - name: d",
                                                   "    kernel: absdiff",
                                                   "    inputs: {a: src, b: {from: src, delay: 1, initial: -3}}",
                                                   "outputs: d",
                                               }),
                                               kOrigin);
  const pl::InputBinding& b = input_named(g.nodes[1], "b");
  ASSERT_TRUE(std::holds_alternative<int>(b.initial));
  EXPECT_EQ(std::get<int>(b.initial), -3);
}

TEST(GraphSpecYaml, LoadsFromAFileNamedInMessages) {
  const auto dir =
      std::filesystem::path(testing::TempDir()) / ("neopipe_graph_spec_file_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string good = (dir / "good.yaml").string();
  const std::string bad = (dir / "bad.yaml").string();
  std::ofstream(good) << kDelayGraphYaml;
  std::ofstream(bad) << yaml_lines({"nodes:", "  - {name: src, kernel: source}", "outputz: src"});

  const pl::GraphSpec g = pl::load_graph_spec(good);
  EXPECT_EQ(g.origin, good);
  EXPECT_EQ(g.nodes.size(), 3U);
  EXPECT_EQ(g.nodes[1].where.file, good);

  try {
    (void)pl::load_graph_spec(bad);
    ADD_FAILURE() << "bad.yaml was accepted";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), bad + ":3:1: unknown key 'outputz' (expected name, description, nodes, outputs)");
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().column, 1);
    EXPECT_EQ(e.message(), "unknown key 'outputz' (expected name, description, nodes, outputs)");
  }

  const std::string missing = (dir / "missing.yaml").string();
  try {
    (void)pl::load_graph_spec(missing);
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot open the graph spec");
  }
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Structural errors: exact "origin:line:column: message"

TEST(GraphSpecErrors, YamlSyntaxError) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - name: src",
                /* 3 */ "    kernel: source: x",  // the second ':' is at column 19
            })),
            "spec.yaml:3:19: illegal map value");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "\t- {name: src, kernel: source}",  // a tab cannot indent
            })),
            "spec.yaml:2:2: illegal block entry");
}

TEST(GraphSpecErrors, NotAMapOrEmpty) {
  EXPECT_EQ(spec_error(yaml_lines({"- src", "- gray"})),
            "spec.yaml:1:1: a graph spec is a map with 'nodes' and 'outputs'");
  // An empty document has no position: the message names the origin only.
  EXPECT_EQ(spec_error(""), "spec.yaml: a graph spec is a map with 'nodes' and 'outputs'");
}

TEST(GraphSpecErrors, UnknownTopLevelKey) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "name: g",
                /* 2 */ "nodes:",
                /* 3 */ "  - {name: src, kernel: source}",
                /* 4 */ "output: src",
            })),
            "spec.yaml:4:1: unknown key 'output' (expected name, description, nodes, outputs)");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes: [{name: src, kernel: source}]",
                /* 2 */ "outputs: src",
                /* 3 */ "  # an indented comment does not move anything",
                /* 4 */ "graph: x",
            })),
            "spec.yaml:4:1: unknown key 'graph' (expected name, description, nodes, outputs)");
}

TEST(GraphSpecErrors, MissingOrEmptyNodes) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "# a comment first",
                /* 2 */ "name: g",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:1: missing 'nodes'");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "name: g",
                /* 2 */ "nodes: []",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:8: 'nodes' must be a non-empty list");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes: {name: src, kernel: source}",
                /* 2 */ "outputs: src",
            })),
            "spec.yaml:1:8: 'nodes' must be a non-empty list");
}

TEST(GraphSpecErrors, MissingOrEmptyOutputs) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
            })),
            "spec.yaml:1:1: missing 'outputs' (the ports whose values leave the graph)");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "outputs: []",
            })),
            "spec.yaml:3:10: 'outputs' must be a port reference or a non-empty list of them");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "outputs: [src, [gray]]",
            })),
            "spec.yaml:3:16: output must be a single value");
}

TEST(GraphSpecErrors, NodeWithoutNameOrKernel) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - kernel: gray",
                /* 4 */ "    inputs: {in: src}",
                /* 5 */ "outputs: src",
            })),
            "spec.yaml:3:5: node without a 'name'");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g2",
                /* 4 */ "    inputs: {in: src}",
                /* 5 */ "outputs: g2",
            })),
            "spec.yaml:3:5: node 'g2' has no 'kernel'");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - src",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:5: a node is a map with 'name' and 'kernel'");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: [source]}",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:25: kernel must be a single value");
}

TEST(GraphSpecErrors, BadNodeName) {
  const char* const rule = "must be letters, digits, '_' or '-', not starting with a digit";
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - name: 2nd",
                /* 3 */ "    kernel: source",
                /* 4 */ "outputs: 2nd",
            })),
            std::string("spec.yaml:2:11: node name '2nd' ") + rule);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {kernel: source, name: a.b}",
                /* 3 */ "outputs: a",
            })),
            std::string("spec.yaml:2:28: node name 'a.b' ") + rule);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - name: \"my node\"",
                /* 3 */ "    kernel: source",
                /* 4 */ "outputs: src",
            })),
            std::string("spec.yaml:2:11: node name 'my node' ") + rule);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - name: ''",
                /* 3 */ "    kernel: source",
                /* 4 */ "outputs: src",
            })),
            std::string("spec.yaml:2:11: node name '' ") + rule);
}

TEST(GraphSpecErrors, DuplicateNodeName) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: src}",
                /* 6 */ "  - kernel: lut",
                /* 7 */ "    name:   g",
                /* 8 */ "outputs: g",
            })),
            "spec.yaml:7:13: duplicate node name 'g'");
}

TEST(GraphSpecErrors, UnknownKeyInANode) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - name: src",
                /* 3 */ "    kernel: source",
                /* 4 */ "    parms: {format: gray}",
                /* 5 */ "outputs: src",
            })),
            "spec.yaml:4:5: unknown key 'parms' in a node (expected name, kernel, params, inputs)");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, input: x}",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:33: unknown key 'input' in a node (expected name, kernel, params, inputs)");
}

TEST(GraphSpecErrors, UnknownKeyInAnInput) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs:",
                /* 6 */ "      in: {from: src, delai: 1}",
                /* 7 */ "outputs: g",
            })),
            "spec.yaml:6:23: unknown key 'delai' in an input (expected from, delay, initial)");
}

TEST(GraphSpecErrors, MalformedInputs) {
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: [src]",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:13: 'inputs' must be a map of input: source");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: {delay: 1}}",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:18: input 'in' has no 'from'");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: src, in: src}",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:23: input 'in' is given twice");
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    params: [1, 2]",
                /* 6 */ "    inputs: {in: src}",
                /* 7 */ "outputs: g",
            })),
            "spec.yaml:5:13: 'params' must be a map of name: value");
}

TEST(GraphSpecErrors, DelayOtherThanZeroOrOne) {
  const char* const message = "'delay' must be 1 (one frame, z^-1) or 0";
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs:",
                /* 6 */ "      a: src",
                /* 7 */ "      b: {from: src, delay: 2}",
                /* 8 */ "outputs: d",
            })),
            std::string("spec.yaml:7:29: ") + message);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs:",
                /* 6 */ "      a: src",
                /* 7 */ "      b:",
                /* 8 */ "        from: src",
                /* 9 */ "        delay: -1",
                /*10 */ "outputs: d",
            })),
            std::string("spec.yaml:9:16: ") + message);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs: {a: src, b: {from: src, delay: true}}",
                /* 6 */ "outputs: d",
            })),
            std::string("spec.yaml:5:44: ") + message);
}

TEST(GraphSpecErrors, InitialWithoutDelay) {
  const char* const message = "'initial' only applies to a delayed input (delay: 1)";
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs:",
                /* 6 */ "      a: src",
                /* 7 */ "      b: {from: src, initial: 0}",
                /* 8 */ "outputs: d",
            })),
            std::string("spec.yaml:7:31: ") + message);
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs:",
                /* 6 */ "      a: src",
                /* 7 */ "      b: {initial: src, from: src, delay: 0}",
                /* 8 */ "outputs: d",
            })),
            std::string("spec.yaml:7:20: ") + message);
}

TEST(GraphSpecErrors, BadPortReference) {
  const auto bad_ref = [](const char* where, const char* text) {
    return std::string("spec.yaml:") + where + ": bad port reference '" + text + "' (expected node or node.port)";
  };
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs:",
                /* 6 */ "      in: a.b.c",
                /* 7 */ "outputs: g",
            })),
            bad_ref("6:11", "a.b.c"));
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: {from: 'src.'}}",
                /* 6 */ "outputs: g",
            })),
            bad_ref("5:25", "src."));
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs: {a: src, b: {from: src, delay: 1, initial: .out}}",
                /* 6 */ "outputs: d",
            })),
            bad_ref("5:56", ".out"));
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "outputs:",
                /* 4 */ "  - src",
                /* 5 */ "  - src.out.x",
            })),
            bad_ref("5:5", "src.out.x"));
  EXPECT_EQ(spec_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source}",
                /* 3 */ "outputs: 9src",
            })),
            bad_ref("3:10", "9src"));
}

TEST(PortRef, ParsesNodeAndPort) {
  const pl::SourceLocation here{"f.yaml", 3, 4};
  const pl::PortRef a = pl::PortRef::parse("blobs", here);
  EXPECT_EQ(a.node, "blobs");
  EXPECT_EQ(a.port, "");
  EXPECT_EQ(a.str(), "blobs");
  const pl::PortRef b = pl::PortRef::parse("split.hi", here);
  EXPECT_EQ(b.node, "split");
  EXPECT_EQ(b.port, "hi");
  EXPECT_EQ(b.str(), "split.hi");
  EXPECT_EQ(b.where.str(), "f.yaml:3:4");
  for (const char* bad : {"", ".", "a.", ".b", "a.b.c", "a b", "1a", "a.1b", "a/b"}) {
    SCOPED_TRACE(bad);
    try {
      (void)pl::PortRef::parse(bad, here);
      ADD_FAILURE() << "accepted";
    } catch (const pl::GraphError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("f.yaml:3:4: bad port reference '") + bad + "' (expected node or node.port)");
    }
  }
}

TEST(SourceLocation, PrintsWhatIsKnown) {
  EXPECT_EQ((pl::SourceLocation{"g.yaml", 12, 7}.str()), "g.yaml:12:7");
  EXPECT_EQ((pl::SourceLocation{"g.yaml", 12, 0}.str()), "g.yaml:12");
  EXPECT_EQ((pl::SourceLocation{"g.yaml", 0, 0}.str()), "g.yaml");
  EXPECT_EQ((pl::SourceLocation{"", 0, 0}.str()), "<graph>");
  const pl::GraphError e({"g.yaml", 2, 9}, "something is wrong");
  EXPECT_EQ(std::string(e.what()), "g.yaml:2:9: something is wrong");
  EXPECT_EQ(e.message(), "something is wrong");
}

// ---------------------------------------------------------------------------------------------
// GraphBuilder

TEST(GraphBuilder, BuildsTheSameSpecAsYaml) {
  pl::GraphBuilder b("<delays in c++>");
  b.node("src", "source", "{format: gray}")
      .node("avg", "lut2", "{expr: \"floor((a + 3*b) / 4)\"}")
      .node("diff", "absdiff")
      .connect("src", "avg.a")
      .connect_delayed("avg", "avg.b", 7)
      .connect("src", "diff.a")
      .connect_delayed("src.out", "diff.b", "src")
      .output("avg")
      .output("diff.out");
  const pl::GraphSpec& built = b.spec();
  const pl::GraphSpec yaml = pl::parse_graph_spec(kDelayGraphYaml, kOrigin);

  EXPECT_EQ(built.origin, "<delays in c++>");
  ASSERT_EQ(built.nodes.size(), yaml.nodes.size());
  for (size_t i = 0; i < yaml.nodes.size(); ++i) {
    const auto& x = built.nodes[i];
    const auto& y = yaml.nodes[i];
    SCOPED_TRACE(y.name);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kernel, y.kernel);
    EXPECT_EQ(x.where.line, 0);  // built in C++: no position
    ASSERT_EQ(x.inputs.size(), y.inputs.size());
    for (const auto& yin : y.inputs) {
      const auto& xin = input_named(x, yin.input);
      EXPECT_EQ(xin.from.str(), yin.from.str());
      EXPECT_EQ(xin.delayed, yin.delayed);
      EXPECT_EQ(xin.initial.index(), yin.initial.index());
      if (const int* v = std::get_if<int>(&yin.initial)) {
        EXPECT_EQ(std::get<int>(xin.initial), *v);
      }
      if (const auto* p = std::get_if<pl::PortRef>(&yin.initial)) {
        EXPECT_EQ(std::get<pl::PortRef>(xin.initial).str(), p->str());
      }
    }
  }
  ASSERT_EQ(built.outputs.size(), yaml.outputs.size());
  for (size_t i = 0; i < yaml.outputs.size(); ++i) EXPECT_EQ(built.outputs[i].str(), yaml.outputs[i].str());

  expect_same_results(built, yaml, random_gray_frames(12, {40, 23}, 11));
}

TEST(GraphBuilder, ParamsAsYamlNodeOrText) {
  YAML::Node params;
  params["value"] = 100;
  pl::GraphBuilder a;
  a.node("src", "source", "{format: gray}").node("bin", "threshold", params).connect("src", "bin.in").output("bin");
  pl::GraphBuilder b;
  b.node("src", "source", "{format: gray}")
      .node("bin", "threshold", "{value: 100}")
      .connect("src", "bin.in")
      .output("bin");
  pl::GraphBuilder other;  // another threshold, so the comparison can tell them apart
  other.node("src", "source", "{format: gray}")
      .node("bin", "threshold", "{value: 200}")
      .connect("src", "bin.in")
      .output("bin");
  const auto frames = random_gray_frames(3, {16, 9}, 5);
  expect_same_results(a.spec(), b.spec(), frames);

  const auto ra = pl::run_frames(pl::compile(a.spec(), pl::standard_kernels()), frames);
  const auto rc = pl::run_frames(pl::compile(other.spec(), pl::standard_kernels()), frames);
  EXPECT_GT(cv::norm(std::get<cv::Mat>(ra[0].outputs[0]), std::get<cv::Mat>(rc[0].outputs[0]), cv::NORM_INF), 0);
}

TEST(GraphBuilder, RejectsBadConnections) {
  pl::GraphBuilder b("<bad>");
  b.node("src", "source").node("g", "gray");
  try {
    b.connect("src", "g");
    ADD_FAILURE() << "a target without an input was accepted";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), "<bad>: connect(): the target must be node.input, got 'g'");
  }
  try {
    b.connect("src", "nope.in");
    ADD_FAILURE() << "an unknown target node was accepted";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), "<bad>: connect(): no node named 'nope'");
  }
  EXPECT_THROW(b.connect("a.b.c", "g.in"), pl::GraphError);
  EXPECT_THROW(b.output("g..out"), pl::GraphError);
  EXPECT_THROW(b.connect_delayed("src", "g.in", "x.y.z"), pl::GraphError);
}
