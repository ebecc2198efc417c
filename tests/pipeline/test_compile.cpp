// Tests of compile() (pipeline/compiled_graph.hpp): every mistake in a graph's meaning is a
// GraphError pointing at the right place of the spec ("spec.yaml:line:column: message"): unknown
// kernels (at the kernel name) and parameters (naming the known ones), bad parameter values (out of
// range, wrong type, an expression error with its character position), references to unknown nodes
// or ports, a multi-output node referenced without a port (a two-output test kernel registered in
// our own KernelRegistry), type mismatches, unconnected inputs, dangling outputs, cycles without a
// delay (the message lists the cycle), missing or duplicate source nodes, and a delayed input whose
// initial port has the wrong type. Legal graphs compile into a producer-before-consumer order: a
// cycle through a delay is fine, every example spec compiles, and examples/blobs.yaml gives exactly
// the blobs of the built-in pipeline::blob_graph().

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)
namespace fs = std::filesystem;

namespace {

const char* const kOrigin = "spec.yaml";

// A registry hands out pointers into itself, so only one that outlives them may: asking a temporary
// (`standard_kernels().all()`) is a compile error, as it once was a read of freed memory (issue 18).
template <class Registry>
concept hands_out_kernels = requires(Registry&& r) {
  std::forward<Registry>(r).all();
  std::forward<Registry>(r).find("gray");
};
static_assert(hands_out_kernels<const pl::KernelRegistry&>);
static_assert(hands_out_kernels<pl::KernelRegistry&>);
static_assert(!hands_out_kernels<pl::KernelRegistry>);  // a temporary
static_assert(!hands_out_kernels<const pl::KernelRegistry>);

// Splits a gray image into its bright part ("hi": pixels > 127, others 0) and its dark part ("lo").
class SplitNode final : public pl::Node {
 public:
  SplitNode()
      : Node({{"in", pl::PortType::gray8}}, {{"hi", pl::PortType::gray8}, {"lo", pl::PortType::gray8}},
             neopipe::kernels::Footprint::point) {}
  void run_rows(pl::NodeIO& io, cv::Range rows) const override {
    const cv::Mat in = io.image(0).rowRange(rows);
    cv::Mat hi = io.out_image(0).rowRange(rows);
    cv::Mat lo = io.out_image(1).rowRange(rows);
    hi.setTo(0);
    lo.setTo(0);
    in.copyTo(hi, in > 127);
    in.copyTo(lo, in <= 127);
  }
};

// The standard kernels plus "split", a node with two outputs.
pl::KernelRegistry registry_with_split() {
  pl::KernelRegistry r = pl::standard_kernels();
  r.add({"split", "test kernel: hi and lo halves of a gray image",
         [](pl::NodeContext&) { return std::make_unique<SplitNode>(); }});
  return r;
}

// Compiles `yaml`, which must fail with a GraphError; returns its what().
std::string compile_error(const std::string& yaml, const pl::KernelRegistry& registry = pl::standard_kernels()) {
  try {
    (void)compile_yaml(yaml, registry);
  } catch (const pl::GraphError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a GraphError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "the spec compiled:\n" << yaml;
  return {};
}

// A spec with a gray source and one more node `kernel` with the given params, fed by the source and
// used as the output: for checking one kernel's parameters. The params value starts at line 4,
// column 14.
std::string one_node_spec(const std::string& kernel, const std::string& params) {
  return "nodes:\n"                                                   // 1
         "  - {name: src, kernel: source, params: {format: gray}}\n"  // 2
         "  - {name: k, kernel: " +
         kernel +
         ",\n"  // 3
         "     params: " +
         params +
         ",\n"                        // 4
         "     inputs: {in: src}}\n"  // 5
         "outputs: k\n";              // 6
}

// Textured bgr frames with bright discs, so thresholds and blobs have work to do.
std::vector<cv::Mat> disc_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, CV_8UC3);
    rng.fill(f, cv::RNG::UNIFORM, 20, 90);
    for (int d = 0; d < 12; ++d) {
      const cv::Point c(rng.uniform(0, size.width), rng.uniform(0, size.height));
      const int radius = rng.uniform(2, 14);
      const auto level = rng.uniform(120, 256);
      cv::circle(f, c, radius, cv::Scalar(level, rng.uniform(100, 256), level), cv::FILLED);
    }
    frames.push_back(f);
  }
  return frames;
}

std::vector<fs::path> example_specs() {
  std::vector<fs::path> specs;
  for (const auto& e : fs::directory_iterator(NEOPIPE_EXAMPLES_DIR)) {
    if (e.path().extension() == ".yaml") specs.push_back(e.path());
  }
  std::sort(specs.begin(), specs.end());
  return specs;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Kernels and parameters

TEST(CompileErrors, UnknownKernelAtTheKernelName) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - name: edges",
                /* 4 */ "    kernel: sobel",
                /* 5 */ "    inputs: {in: src}",
                /* 6 */ "outputs: edges",
            })),
            "spec.yaml:4:13: unknown kernel 'sobel' (known: absdiff, add, and, blobs, bool3x3, conv3x3, convert, "
            "gray, histogram, image, lut, lut2, max, min, or, source, sub, threshold, value_blobs, xor)");
}

TEST(CompileErrors, UnknownParameterNamesTheKnownOnes) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: bin",
                /* 4 */ "    kernel: threshold",
                /* 5 */ "    params:",
                /* 6 */ "      value: 40",
                /* 7 */ "      treshold: 40",
                /* 8 */ "    inputs: {in: src}",
                /* 9 */ "outputs: bin",
            })),
            "spec.yaml:7:7: unknown parameter 'treshold' for kernel 'threshold' (known: high, value)");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {colour: gray}}",
                /* 3 */ "outputs: src",
            })),
            "spec.yaml:2:42: unknown parameter 'colour' for kernel 'source' (known: format)");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - {name: g, kernel: gray, params: {fast: true}, inputs: {in: src}}",
                /* 4 */ "outputs: g",
            })),
            "spec.yaml:3:38: unknown parameter 'fast' for kernel 'gray' (it takes none)");
}

TEST(CompileErrors, BadParameterValues) {
  struct Case {
    const char* kernel;
    const char* params;  // starts at line 4, column 14 of one_node_spec
    const char* expected;
  };
  const Case cases[] = {
      {"threshold", "{value: 300}", "spec.yaml:4:22: threshold parameter 'value': 300 is out of range -1..255"},
      {"threshold", "{value: -2}", "spec.yaml:4:22: threshold parameter 'value': -2 is out of range -1..255"},
      {"threshold", "{value: 12abc}", "spec.yaml:4:22: threshold parameter 'value': expected an integer"},
      {"threshold", "{value: 1.5}", "spec.yaml:4:22: threshold parameter 'value': expected an integer"},
      {"threshold", "{value: [1]}", "spec.yaml:4:22: threshold parameter 'value': expected a single value"},
      {"threshold", "{high: 0}", "spec.yaml:4:21: threshold parameter 'high': 0 is out of range 1..255"},
      {"conv3x3", "{shift: 17}", "spec.yaml:4:22: conv3x3 parameter 'shift': 17 is out of range 0..16"},
      {"conv3x3", "{weights: [1, 2, 3]}", "spec.yaml:4:24: conv3x3 parameter 'weights': expected 9 entries, got 3"},
      {"conv3x3", "{weights: [1, 2, 3, 4, x, 6, 7, 8, 9]}",
       "spec.yaml:4:24: conv3x3 parameter 'weights': entry 4 must be an integer in -65535..65535"},
      {"conv3x3", "{weights: 5}", "spec.yaml:4:24: conv3x3 parameter 'weights': expected a list of integers"},
      {"conv3x3", "{preset: blur}",
       "spec.yaml:4:23: conv3x3 parameter 'preset': 'blur' is not one of identity, smooth, sobel_x, sobel_y, "
       "laplace, sharpen"},
      {"conv3x3", "{output: u8}", "spec.yaml:4:23: conv3x3 parameter 'output': 'u8' is not one of gray8, s16"},
      {"conv3x3", "{border: constant, border_value: 256}",
       "spec.yaml:4:47: conv3x3 parameter 'border_value': 256 is out of range 0..255"},
      {"bool3x3", "{op: erode, border: constant, border_value: 2}",
       "spec.yaml:4:58: bool3x3 parameter 'border_value': 2 is out of range 0..1"},
      {"bool3x3", "{op: open}", "spec.yaml:4:19: bool3x3 parameter 'op': 'open' is not one of erode, dilate"},
      {"bool3x3", "{op: erode, pattern: '111 111 111'}",
       "spec.yaml:4:19: bool3x3 parameter 'op': give exactly one of op (erode | dilate), pattern (hit-or-miss), "
       "expr or table (512 values)"},
      {"bool3x3", "{table: [0, 1]}", "spec.yaml:4:22: bool3x3 parameter 'table': expected 512 entries, got 2"},
      {"convert", "{abs: maybe}", "spec.yaml:4:20: convert parameter 'abs': expected true or false"},
      {"convert", "{shift: 16}", "spec.yaml:4:22: convert parameter 'shift': 16 is out of range 0..15"},
      {"blobs", "{connectivity: 6}", "spec.yaml:4:29: blobs parameter 'connectivity': must be 4 or 8"},
      {"blobs", "{threshold: 256}", "spec.yaml:4:26: blobs parameter 'threshold': 256 is out of range -1..255"},
      {"lut", "{table: [1, 2]}", "spec.yaml:4:22: lut parameter 'table': expected 256 entries, got 2"},
      {"lut", "{expr: a, table: [1]}",
       "spec.yaml:4:21: lut parameter 'expr': give exactly one of 'table' (256 values) or 'expr' (in terms of a)"},
      // An expression error gives the character position inside the expression.
      {"lut", "{expr: \"a +* 2\"}",
       "spec.yaml:4:21: lut parameter 'expr': unexpected '*' at character 4 of \"a +* 2\""},
      {"lut", "{expr: 255 - b}",
       "spec.yaml:4:21: lut parameter 'expr': unknown name 'b' (variables: a) at character 7 of \"255 - b\""},
      {"bool3x3", "{expr: 'c && (n || s'}",
       "spec.yaml:4:21: bool3x3 parameter 'expr': expected ')' at character 13 of \"c && (n || s\""},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.kernel) + " " + c.params);
    EXPECT_EQ(compile_error(one_node_spec(c.kernel, c.params)), c.expected);
  }
}

TEST(CompileErrors, MissingRequiredParameterPointsAtTheKernel) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: avg",
                /* 4 */ "    kernel: lut2",
                /* 5 */ "    params: {}",
                /* 6 */ "    inputs: {a: src, b: src}",
                /* 7 */ "outputs: avg",
            })),
            "spec.yaml:4:13: lut2 parameter 'expr': required: f(a, b), e.g. \"(a + 7*b + 4) / 8\"");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - {name: mask, kernel: image, params: {}}",
                /* 4 */ "  - {name: m, kernel: and, inputs: {a: src, b: mask}}",
                /* 5 */ "outputs: m",
            })),
            "spec.yaml:3:26: image parameter 'path': required: the image file to load");
}

TEST(CompileErrors, ImageThatCannotBeRead) {
  const std::string err = compile_error(yaml_lines({
      /* 1 */ "nodes:",
      /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
      /* 3 */ "  - {name: mask, kernel: image, params: {path: /nonexistent/mask.png}}",
      /* 4 */ "  - {name: m, kernel: and, inputs: {a: src, b: mask}}",
      /* 5 */ "outputs: m",
  }));
  EXPECT_EQ(err, "spec.yaml:3:48: image parameter 'path': cannot read '/nonexistent/mask.png' as an image");
}

// ---------------------------------------------------------------------------------------------
// References, ports and types

TEST(CompileErrors, UnknownNodeInAnInput) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: scr}",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:18: no node named 'scr'");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "outputs: [src, ghost]",
            })),
            "spec.yaml:3:16: no node named 'ghost'");
}

TEST(CompileErrors, UnknownPortOrInput) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: src.output}",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:18: node 'src' has no output 'output' (outputs: out)");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - {name: g, kernel: gray, inputs: {in: src}}",
                /* 4 */ "outputs: g.gray",
            })),
            "spec.yaml:4:10: node 'g' has no output 'gray' (outputs: out)");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {image: src}",
                /* 6 */ "outputs: g",
            })),
            "spec.yaml:5:14: node 'g' (gray) has no input 'image' (inputs: in)");
}

TEST(CompileErrors, MultiOutputNodeNeedsAPort) {
  const pl::KernelRegistry registry = registry_with_split();
  EXPECT_EQ(compile_error(yaml_lines({
                              /* 1 */ "nodes:",
                              /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                              /* 3 */ "  - {name: sp, kernel: split, inputs: {in: src}}",
                              /* 4 */ "  - {name: both, kernel: or, inputs: {a: sp.hi, b: sp}}",
                              /* 5 */ "outputs: both",
                          }),
                          registry),
            "spec.yaml:4:52: node 'sp' has 2 outputs; name one: hi, lo");
  EXPECT_EQ(compile_error(yaml_lines({
                              /* 1 */ "nodes:",
                              /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                              /* 3 */ "  - {name: sp, kernel: split, inputs: {in: src}}",
                              /* 4 */ "outputs: [sp.lo, sp.mid]",
                          }),
                          registry),
            "spec.yaml:4:18: node 'sp' has no output 'mid' (outputs: hi, lo)");
  // Each port of a multi-output node must go somewhere.
  EXPECT_EQ(compile_error(yaml_lines({
                              /* 1 */ "nodes:",
                              /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                              /* 3 */ "  - {name: sp, kernel: split, inputs: {in: src}}",
                              /* 4 */ "outputs: sp.hi",
                          }),
                          registry),
            "spec.yaml:3:5: dangling port: output 'lo' of node 'sp' goes nowhere (connect it or list it under "
            "outputs)");
  // Named ports are wired to the right consumers: hi | lo gives the input back.
  pl::CompiledGraph g = compile_yaml(yaml_lines({
                                         "nodes:",
                                         "  - {name: src, kernel: source, params: {format: gray}}",
                                         "  - {name: sp, kernel: split, inputs: {in: src}}",
                                         "  - {name: both, kernel: or, inputs: {a: sp.hi, b: sp.lo}}",
                                         "outputs: [both, sp.hi]",
                                     }),
                                     registry);
  EXPECT_EQ(g.output_names(), (std::vector<std::string>{"both", "sp.hi"}));
  cv::Mat frame(9, 13, CV_8UC1);
  cv::randu(frame, 0, 256);
  const auto results = pl::run_frames(std::move(g), {frame});
  ASSERT_EQ(results.size(), 1U);
  EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[0].outputs[0]), frame, cv::NORM_INF), 0);
  cv::Mat hi = frame.clone();
  hi.setTo(0, frame <= 127);
  EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[0].outputs[1]), hi, cv::NORM_INF), 0);
}

TEST(CompileErrors, TypeMismatch) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: gx",
                /* 4 */ "    kernel: conv3x3",
                /* 5 */ "    params: {preset: sobel_x, output: s16}",
                /* 6 */ "    inputs: {in: src}",
                /* 7 */ "  - name: bin",
                /* 8 */ "    kernel: threshold",
                /* 9 */ "    params: {value: otsu}",
                /*10 */ "    inputs:",
                /*11 */ "      in: gx",
                /*12 */ "outputs: bin",
            })),
            "spec.yaml:11:11: type mismatch: input 'in' of node 'bin' takes gray8 but 'gx' is s16");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - {name: bin, kernel: threshold, params: {value: 9}, inputs: {in: src.out}}",
                /* 4 */ "outputs: bin",
            })),
            "spec.yaml:3:69: type mismatch: input 'in' of node 'bin' takes gray8 but 'src.out' is bgr8");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - {name: h, kernel: histogram, inputs: {in: src}}",
                /* 4 */ "  - {name: b, kernel: blobs, params: {threshold: 0}, inputs: {in: src, weights: h}}",
                /* 5 */ "outputs: b",
            })),
            "spec.yaml:4:81: type mismatch: input 'weights' of node 'b' takes gray8 but 'h' is histogram");
}

TEST(CompileErrors, UnconnectedRequiredInput) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: d",
                /* 4 */ "    kernel: absdiff",
                /* 5 */ "    inputs: {a: src}",
                /* 6 */ "outputs: d",
            })),
            "spec.yaml:3:5: input 'b' of node 'd' (absdiff) is not connected");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - {name: inv, kernel: lut, params: {expr: 255 - a}}",
                /* 4 */ "outputs: [inv, src]",
            })),
            "spec.yaml:3:5: input 'in' of node 'inv' (lut) is not connected");
  // An optional input (the blobs' weights) may stay unconnected.
  EXPECT_NO_THROW(compile_yaml(yaml_lines({
      "nodes:",
      "  - {name: src, kernel: source, params: {format: gray}}",
      "  - {name: b, kernel: blobs, params: {threshold: 0}, inputs: {in: src}}",
      "outputs: b",
  })));
}

TEST(CompileErrors, DanglingOutput) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
                /* 3 */ "  - name: g",
                /* 4 */ "    kernel: gray",
                /* 5 */ "    inputs: {in: src}",
                /* 6 */ "  - name: h",
                /* 7 */ "    kernel: histogram",
                /* 8 */ "    inputs: {in: g}",
                /* 9 */ "outputs: g",
            })),
            "spec.yaml:6:5: dangling port: output 'out' of node 'h' goes nowhere (connect it or list it under "
            "outputs)");
  // The source too: a graph that ignores its frames is a mistake.
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - {name: h, kernel: histogram, inputs: {in: h2}}",
                /* 4 */ "  - {name: h2, kernel: lut, params: {expr: a}, inputs: {in: h2}}",
                /* 5 */ "outputs: h",
            })),
            "spec.yaml:2:5: dangling port: output 'out' of node 'src' goes nowhere (connect it or list it under "
            "outputs)");
}

TEST(CompileErrors, CycleWithoutDelayListsTheCycle) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - name: a",
                /* 4 */ "    kernel: lut",
                /* 5 */ "    params: {expr: a}",
                /* 6 */ "    inputs: {in: a}",
                /* 7 */ "outputs: [a, src]",
            })),
            "spec.yaml:6:18: cycle without a delay: a -> a (a cycle is legal only through an input marked 'delay: 1')");

  const std::string two = compile_error(yaml_lines({
      /* 1 */ "nodes:",
      /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
      /* 3 */ "  - name: a",
      /* 4 */ "    kernel: max",
      /* 5 */ "    inputs: {a: src, b: b}",
      /* 6 */ "  - name: b",
      /* 7 */ "    kernel: lut",
      /* 8 */ "    params: {expr: a / 2}",
      /* 9 */ "    inputs: {in: a}",
      /*10 */ "outputs: a",
  }));
  // Where the walk around the cycle starts is the compiler's choice, but the error points at one of
  // the cycle's two edges (b's input 'a' at 9:18, a's input 'b' at 5:25) and lists the cycle, closed,
  // in data-flow order.
  const std::string at = two.substr(0, two.find(" cycle"));
  EXPECT_TRUE(at == "spec.yaml:9:18:" || at == "spec.yaml:5:25:") << two;
  const std::string tail = " (a cycle is legal only through an input marked 'delay: 1')";
  EXPECT_TRUE(two.ends_with("cycle without a delay: a -> b -> a" + tail) ||
              two.ends_with("cycle without a delay: b -> a -> b" + tail))
      << two;

  const std::string three = compile_error(yaml_lines({
      /* 1 */ "nodes:",
      /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
      /* 3 */ "  - {name: x, kernel: add, inputs: {a: src, b: z}}",
      /* 4 */ "  - {name: y, kernel: lut, params: {expr: a}, inputs: {in: x}}",
      /* 5 */ "  - {name: z, kernel: lut, params: {expr: a}, inputs: {in: y}}",
      /* 6 */ "outputs: x",
  }));
  EXPECT_NE(three.find("cycle without a delay: "), std::string::npos) << three;
  EXPECT_TRUE(three.find("x -> y -> z -> x") != std::string::npos ||
              three.find("y -> z -> x -> y") != std::string::npos ||
              three.find("z -> x -> y -> z") != std::string::npos)
      << three;
}

TEST(Compile, CycleThroughADelayIsLegal) {
  pl::CompiledGraph g = compile_yaml(yaml_lines({
      "nodes:",
      "  - {name: src, kernel: source, params: {format: gray}}",
      "  - name: a",
      "    kernel: max",
      "    inputs: {a: src, b: {from: b, delay: 1, initial: 0}}",
      "  - name: b",
      "    kernel: lut",
      "    params: {expr: a / 2}",
      "    inputs: {in: a}",
      "outputs: a",
  }));
  EXPECT_TRUE(g.has_delays());
  // a[t] = max(src[t], b[t-1]) with b = round(a / 2) and b[-1] = 0, checked on constant frames.
  std::vector<cv::Mat> frames;
  for (int v : {200, 10, 10, 120, 0}) frames.emplace_back(cv::Size(5, 3), CV_8UC1, cv::Scalar(v));
  const auto results = pl::run_frames(std::move(g), frames, {.threads = 2});
  const int expected[] = {200, 100, 50, 120, 60};
  ASSERT_EQ(results.size(), 5U);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[i].outputs[0]), cv::Mat(3, 5, CV_8UC1, cv::Scalar(expected[i])),
                       cv::NORM_INF),
              0)
        << "frame " << i;
  }
}

TEST(CompileErrors, SourceNodes) {
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: l, kernel: lut, params: {expr: a}, inputs: {in: l}}",
                /* 3 */ "outputs: l",
            })),
            "spec.yaml: the graph has no node of kernel 'source' (the frames it processes)");
  EXPECT_EQ(compile_error(yaml_lines({
                /* 1 */ "nodes:",
                /* 2 */ "  - {name: src, kernel: source, params: {format: gray}}",
                /* 3 */ "  - {name: cam2, kernel: source, params: {format: gray}}",
                /* 4 */ "  - {name: d, kernel: absdiff, inputs: {a: src, b: cam2}}",
                /* 5 */ "outputs: d",
            })),
            "spec.yaml:3:5: a graph has one 'source' node; 'src' is already one");
}

TEST(CompileErrors, DelayedInitialPort) {
  const char* const bg_lines[] = {
      /* 1 */ "nodes:",
      /* 2 */ "  - {name: src, kernel: source, params: {format: bgr}}",
      /* 3 */ "  - {name: gray, kernel: gray, inputs: {in: src}}",
      /* 4 */ "  - name: bg",
      /* 5 */ "    kernel: lut2",
      /* 6 */ "    params: {expr: \"floor((a + 15*b + 8) / 16)\"}",
      /* 7 */ "    inputs:",
      /* 8 */ "      a: gray",
  };
  const auto spec_with = [&](const char* line9) {
    std::string s;
    for (const char* l : bg_lines) s.append(l).append("\n");
    return s + line9 + "\noutputs: bg\n";
  };
  EXPECT_EQ(compile_error(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: src}")),
            "spec.yaml:9:40: type mismatch: the initial value of input 'b' of node 'bg' must be gray8 but 'src' is "
            "bgr8");
  EXPECT_EQ(compile_error(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: grey}")),
            "spec.yaml:9:40: no node named 'grey'");
  // On the first frame bg would wait for itself.
  EXPECT_EQ(compile_error(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: bg}")),
            "spec.yaml:9:40: cycle without a delay: bg -> bg (a cycle is legal only through an input marked "
            "'delay: 1')");
  EXPECT_NO_THROW(compile_yaml(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: gray}")));
  EXPECT_NO_THROW(compile_yaml(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: 128}")));
  // Both ends of the range are legal (tests/mutation/mutants.json, P11).
  EXPECT_NO_THROW(compile_yaml(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: 0}")));
  EXPECT_NO_THROW(compile_yaml(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: 255}")));
  // A constant must fit the port's pixels, not wrap or saturate silently.
  EXPECT_EQ(compile_error(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: 300}")),
            "spec.yaml:9:7: the initial value of input 'b' of node 'bg' is 300, outside the gray8 range 0..255");
  EXPECT_EQ(compile_error(spec_with(/* 9 */ "      b: {from: bg, delay: 1, initial: -1}")),
            "spec.yaml:9:7: the initial value of input 'b' of node 'bg' is -1, outside the gray8 range 0..255");
}

TEST(CompileErrors, SpecsBuiltInCpp) {
  // Without positions, messages name the origin only.
  pl::GraphBuilder empty("<empty>");
  try {
    (void)pl::compile(empty.spec(), pl::standard_kernels());
    ADD_FAILURE() << "an empty graph compiled";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), "<empty>: the graph has no nodes");
  }
  pl::GraphBuilder no_outputs("<no outputs>");
  no_outputs.node("src", "source", "{format: bgr}");
  try {
    (void)pl::compile(no_outputs.spec(), pl::standard_kernels());
    ADD_FAILURE() << "a graph without outputs compiled";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), "<no outputs>: the graph declares no outputs");
  }
  pl::GraphBuilder twice("<twice>");
  twice.node("src", "source", "{format: bgr}").node("g", "gray").node("g", "gray").connect("src", "g.in").output("g");
  try {
    (void)pl::compile(twice.spec(), pl::standard_kernels());
    ADD_FAILURE() << "a duplicate node name compiled";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()), "<twice>: duplicate node name 'g'");
  }
}

// A node with no 'params' (the key absent, empty or null) takes every default. (Regression test:
// ParamReader once answered a missing map with a default-constructed YAML::Node, which yaml-cpp
// treats as a defined null, so every parameter read as given and invalid.)
TEST(Compile, NodeWithoutParamsTakesTheDefaults) {
  // Defaults: source bgr, threshold otsu, blobs threshold 0 and 8-connected: the built-in blob graph.
  const auto frames = disc_frames(3, {64, 48}, 99);
  const auto expected = pl::run_frames(pl::compile(pl::blob_graph(), pl::standard_kernels()), frames);
  for (const char* no_params : {"", ", params: ", ", params: ~"}) {
    SCOPED_TRACE(std::string("params written as '") + no_params + "'");
    const std::string p(no_params);
    const std::string yaml =
        "nodes:\n"
        "  - {name: src, kernel: source" +
        p +
        "}\n"
        "  - {name: gray, kernel: gray, inputs: {in: src}}\n"
        "  - {name: binary, kernel: threshold" +
        p +
        ", inputs: {in: gray}}\n"
        "  - {name: blobs, kernel: blobs" +
        p +
        ", inputs: {in: binary, weights: gray}}\n"
        "outputs: blobs\n";
    const auto results = pl::run_frames(compile_yaml(yaml), frames);
    ASSERT_EQ(results.size(), frames.size());
    for (size_t f = 0; f < frames.size(); ++f) {
      expect_same_blobs(std::get<pl::BlobList>(results[f].outputs[0]), std::get<pl::BlobList>(expected[f].outputs[0]));
    }
  }
  // The same through GraphBuilder, whose params default to an empty YAML node.
  pl::GraphBuilder b("<defaults>");
  b.node("src", "source")
      .node("gray", "gray")
      .node("bin", "threshold")
      .connect("src", "gray.in")
      .connect("gray", "bin.in")
      .output("bin");
  EXPECT_NO_THROW(pl::compile(b.spec(), pl::standard_kernels()));
}

// A port used only as the initial value of a delayed input is read on the first frame, so it is
// not dangling (regression: compile() once counted only ordinary edges and outputs as uses).
TEST(Compile, PortUsedOnlyAsInitialValueIsNotDangling) {
  pl::CompiledGraph g = compile_yaml(yaml_lines({
      "nodes:",
      "  - {name: src, kernel: source, params: {format: gray}}",
      "  - {name: start, kernel: lut, params: {expr: 255 - a}, inputs: {in: src}}",
      "  - name: d",
      "    kernel: absdiff",
      "    inputs: {a: src, b: {from: src, delay: 1, initial: start}}",
      "outputs: d",
  }));
  cv::Mat f0(4, 4, CV_8UC1, cv::Scalar(10));
  cv::Mat f1(4, 4, CV_8UC1, cv::Scalar(30));
  const auto results = pl::run_frames(std::move(g), {f0, f1});
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[0].outputs[0]), cv::Mat(4, 4, CV_8UC1, cv::Scalar(235)), cv::NORM_INF),
            0);
  EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[1].outputs[0]), cv::Mat(4, 4, CV_8UC1, cv::Scalar(20)), cv::NORM_INF),
            0);
}

// ---------------------------------------------------------------------------------------------
// Compiled graphs

TEST(Compile, OrdersProducersBeforeConsumers) {
  // Declared consumers first; the compiled order must put every producer first. As declared: the
  // folding pass would merge the threshold into blobs.
  const pl::CompiledGraph g = pl::compile_as_declared(
      pl::parse_graph_spec(
          yaml_lines({
              "nodes:",
              "  - {name: blobs, kernel: blobs, params: {threshold: 0}, inputs: {in: binary, weights: gray}}",
              "  - {name: hist, kernel: histogram, inputs: {in: gray}}",
              "  - {name: binary, kernel: threshold, params: {value: otsu}, inputs: {in: gray}}",
              "  - {name: gray, kernel: gray, inputs: {in: src}}",
              "  - {name: src, kernel: source, params: {format: bgr}}",
              "outputs: [blobs, hist, gray]",
          }),
          kOrigin),
      pl::standard_kernels());
  ASSERT_EQ(g.nodes().size(), 5U);
  for (size_t c = 0; c < g.nodes().size(); ++c) {
    for (const auto& in : g.nodes()[c].inputs) {
      if (!in.from.valid() || in.delayed) continue;
      EXPECT_LT(static_cast<size_t>(in.from.node), c) << g.nodes()[c].name;
    }
  }
  EXPECT_EQ(g.nodes()[static_cast<size_t>(g.source())].name, "src");
  EXPECT_EQ(g.source_type(), pl::PortType::bgr8);
  EXPECT_FALSE(g.has_delays());
  EXPECT_EQ(g.origin(), kOrigin);
  ASSERT_EQ(g.outputs().size(), 3U);
  EXPECT_EQ(g.nodes()[static_cast<size_t>(g.outputs()[0].node)].name, "blobs");
  EXPECT_EQ(g.nodes()[static_cast<size_t>(g.outputs()[1].node)].name, "hist");
  EXPECT_EQ(g.type_of(g.outputs()[0]), pl::PortType::blobs);
  EXPECT_EQ(g.type_of(g.outputs()[1]), pl::PortType::histogram);
  EXPECT_EQ(g.type_of(g.outputs()[2]), pl::PortType::gray8);
  EXPECT_EQ(g.find_output(pl::PortType::blobs), std::optional<size_t>(0));
  EXPECT_EQ(g.find_output(pl::PortType::gray8), std::optional<size_t>(2));
  EXPECT_EQ(g.find_output(pl::PortType::s16), std::nullopt);
  // The unconnected optional input stays invalid; the connected one resolves.
  const auto& blobs = g.nodes()[static_cast<size_t>(g.outputs()[0].node)];
  ASSERT_EQ(blobs.inputs.size(), 2U);
  EXPECT_TRUE(blobs.inputs[1].from.valid());
  EXPECT_EQ(g.nodes()[static_cast<size_t>(blobs.inputs[1].from.node)].name, "gray");
}

TEST(Compile, DelayedInputsRecordTheirInitialValue) {
  const pl::CompiledGraph g = compile_yaml(yaml_lines({
      "nodes:",
      "  - {name: src, kernel: source, params: {format: gray}}",
      "  - {name: d1, kernel: absdiff, inputs: {a: src, b: {from: src, delay: 1, initial: 42}}}",
      "  - {name: d2, kernel: absdiff, inputs: {a: src, b: {from: src, delay: 1, initial: d1}}}",
      "outputs: [d1, d2]",
  }));
  EXPECT_TRUE(g.has_delays());
  const auto node = [&](const std::string& name) -> const pl::CompiledNode& {
    for (const auto& n : g.nodes()) {
      if (n.name == name) return n;
    }
    throw std::runtime_error("no node " + name);
  };
  const auto& d1 = node("d1").inputs[1];
  EXPECT_TRUE(d1.delayed);
  EXPECT_EQ(d1.initial_fill, 42);
  EXPECT_FALSE(d1.initial_from.valid());
  const auto& d2 = node("d2").inputs[1];
  EXPECT_TRUE(d2.delayed);
  ASSERT_TRUE(d2.initial_from.valid());
  EXPECT_EQ(g.nodes()[static_cast<size_t>(d2.initial_from.node)].name, "d1");
  EXPECT_FALSE(node("d2").inputs[0].delayed);
}

TEST(Compile, ImagePathIsRelativeToTheSpecFile) {
  const fs::path dir = fs::path(testing::TempDir()) / ("neopipe_compile_image_" + std::to_string(::getpid()));
  fs::create_directories(dir / "masks");
  cv::Mat mask(6, 8, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(2, 1, 4, 3)).setTo(255);
  ASSERT_TRUE(cv::imwrite((dir / "masks" / "m.png").string(), mask));
  const std::string spec = (dir / "masked.yaml").string();
  std::ofstream(spec) << yaml_lines({
      "nodes:",
      "  - {name: src, kernel: source, params: {format: gray}}",
      "  - {name: mask, kernel: image, params: {path: masks/m.png}}",
      "  - {name: masked, kernel: and, inputs: {a: src, b: mask}}",
      "outputs: masked",
  });
  cv::Mat frame(6, 8, CV_8UC1);
  cv::randu(frame, 0, 256);
  const auto results = pl::run_frames(pl::compile(pl::load_graph_spec(spec), pl::standard_kernels()), {frame});
  cv::Mat expected;
  cv::bitwise_and(frame, mask, expected);
  ASSERT_EQ(results.size(), 1U);
  EXPECT_EQ(cv::norm(std::get<cv::Mat>(results[0].outputs[0]), expected, cv::NORM_INF), 0);
  fs::remove_all(dir);
}

TEST(Compile, EveryExampleCompiles) {
  const auto specs = example_specs();
  ASSERT_GE(specs.size(), 3U) << "examples folder: " << NEOPIPE_EXAMPLES_DIR;
  for (const auto& path : specs) {
    SCOPED_TRACE(path.string());
    const pl::CompiledGraph g = pl::compile(pl::load_graph_spec(path.string()), pl::standard_kernels());
    EXPECT_GE(g.source(), 0);
    EXPECT_TRUE(g.find_output(pl::PortType::blobs).has_value());
  }
}

namespace {

// The example file and the built-in graph give the same blob tables on `frames`.
void expect_example_equals_built_in(const std::string& example, const pl::GraphSpec& built_in_spec,
                                    const std::vector<cv::Mat>& frames) {
  const auto from_file = pl::run_frames(
      pl::compile(pl::load_graph_spec(std::string(NEOPIPE_EXAMPLES_DIR) + "/" + example), pl::standard_kernels()),
      frames, {.threads = 2});
  const auto built_in = pl::run_frames(pl::compile(built_in_spec, pl::standard_kernels()), frames, {.threads = 2});
  ASSERT_EQ(from_file.size(), frames.size());
  ASSERT_EQ(built_in.size(), frames.size());
  size_t total = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    ASSERT_EQ(from_file[f].outputs.size(), 1U);
    ASSERT_EQ(built_in[f].outputs.size(), 1U);
    const auto& a = std::get<pl::BlobList>(from_file[f].outputs[0]);
    const auto& b = std::get<pl::BlobList>(built_in[f].outputs[0]);
    expect_same_blobs(a, b);
    total += a.size();
  }
  EXPECT_GT(total, frames.size());  // the frames do have blobs, so the comparison means something
}

}  // namespace

TEST(Compile, BlobsExampleEqualsTheBuiltInBlobGraph) {
  expect_example_equals_built_in("blobs.yaml", pl::blob_graph(), disc_frames(8, {96, 72}, 2024));
}

TEST(Compile, MarblesExampleEqualsTheBuiltInMarbleGraph) {
  std::vector<cv::Mat> gray;
  for (const cv::Mat& f : disc_frames(8, {96, 72}, 77)) {
    cv::Mat g;
    cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
    gray.push_back(g);
  }
  expect_example_equals_built_in("marbles.yaml", pl::marble_graph(), gray);
}

TEST(Compile, BlobGraphOptions) {
  const pl::GraphSpec gray = pl::blob_graph({.threshold = 100, .connectivity = 4, .source = pl::PortType::gray8});
  const pl::CompiledGraph g = pl::compile(gray, pl::standard_kernels());
  EXPECT_EQ(g.source_type(), pl::PortType::gray8);
  EXPECT_EQ(g.nodes().size(), 2U);  // no gray node, and the threshold folded into blobs
  EXPECT_EQ(pl::compile_as_declared(gray, pl::standard_kernels()).nodes().size(), 3U);
  // A fixed threshold of 100 with 4-connectivity: two diagonal pixels are two blobs.
  cv::Mat frame(5, 5, CV_8UC1, cv::Scalar(0));
  frame.at<std::uint8_t>(1, 1) = 101;
  frame.at<std::uint8_t>(2, 2) = 200;
  frame.at<std::uint8_t>(4, 4) = 100;  // not above the threshold
  const auto results = pl::run_frames(pl::compile(gray, pl::standard_kernels()), {frame});
  const auto& blobs = std::get<pl::BlobList>(results.at(0).outputs.at(0));
  ASSERT_EQ(blobs.size(), 2U);
  EXPECT_EQ(blobs[0].x0, 1);
  EXPECT_EQ(blobs[1].x0, 2);
}
