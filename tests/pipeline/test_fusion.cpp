// Fusion (pipeline/fusion.hpp): which nodes the scheduler fuses, and that fusing changes nothing.
// plan_fusion groups single-use chains of row-computable nodes and leaves alone graph outputs,
// nodes used twice or through a delay, and Otsu's threshold (it needs its whole input first). Every
// graph compared here has at least one fused group (a graph without one runs the same steps either
// way) and gives bit-identical outputs fused and unfused, for stripes of 1, 2, 3 and 7 rows and the
// automatic size, on heights that do not divide into stripes, with 1, 2 and 8 threads.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>
#include <vector>

#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/fusion.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/node.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)

namespace {

// Node names of each fused group, sink last.
std::vector<std::vector<std::string>> groups_of(const pl::CompiledGraph& g) {
  std::vector<std::vector<std::string>> out;
  for (const auto& members : pl::plan_fusion(g)) {
    std::vector<std::string> names;
    for (const int m : members) names.push_back(g.nodes()[static_cast<size_t>(m)].name);
    out.push_back(names);
  }
  return out;
}

// The benchmark's four-stage chain: 3x3 smooth -> threshold -> 3x3 opening -> blobs.
const char* const kChain = R"(
nodes:
  - {name: src, kernel: source, params: {format: gray}}
  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: src}}
  - {name: binary, kernel: threshold, params: {value: 120}, inputs: {in: smooth}}
  - {name: eroded, kernel: bool3x3, params: {op: erode}, inputs: {in: binary}}
  - {name: opened, kernel: bool3x3, params: {op: dilate}, inputs: {in: eroded}}
  - {name: blobs, kernel: blobs, inputs: {in: opened, weights: src}}
outputs: [blobs]
)";

// Every row-computable kernel in one fusable tree, with constant borders and a 16-bit branch.
const char* const kTree = R"(
nodes:
  - {name: src, kernel: source, params: {format: bgr}}
  - {name: gray, kernel: gray, inputs: {in: src}}
  - {name: gx, kernel: conv3x3, params: {preset: sobel_x, output: s16, border: constant, border_value: 200}, inputs: {in: gray}}
  - {name: mx, kernel: convert, params: {abs: true, shift: 2}, inputs: {in: gx}}
  - {name: inv, kernel: lut, params: {expr: "255 - a"}, inputs: {in: mx}}
  - {name: g2, kernel: gray, inputs: {in: src}}
  - {name: sharp, kernel: conv3x3, params: {preset: sharpen}, inputs: {in: g2}}
  - {name: mix, kernel: lut2, params: {expr: "(a + 3*b) / 4"}, inputs: {a: inv, b: sharp}}
  - {name: bin, kernel: threshold, params: {value: 100}, inputs: {in: mix}}
  - {name: edge, kernel: bool3x3, params: {expr: "c && (n + s + e + w) < 4", border: constant, border_value: 1}, inputs: {in: bin}}
  - {name: grown, kernel: bool3x3, params: {op: dilate}, inputs: {in: edge}}
  - {name: out, kernel: max, inputs: {a: grown, b: bin2}}
  - {name: g3, kernel: gray, inputs: {in: src}}
  - {name: bin2, kernel: threshold, params: {value: 200}, inputs: {in: g3}}
outputs: [out]
)";

std::vector<cv::Mat> frames_for(const pl::CompiledGraph& g, cv::Size size, int count) {
  cv::RNG rng(99);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, g.source_type() == pl::PortType::bgr8 ? CV_8UC3 : CV_8UC1);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(f, f, {5, 5}, 1.2);  // some structure, so thresholds and morphology do something
    frames.push_back(f);
  }
  return frames;
}

void expect_fused_equals_unfused(const std::function<pl::CompiledGraph()>& make, cv::Size size) {
  // Without a fused group, fuse = true runs exactly the unfused steps, and the comparison below
  // would hold whatever fusion did.
  ASSERT_FALSE(pl::plan_fusion(make()).empty()) << "the graph has no fused group: nothing to compare";
  const auto frames = frames_for(make(), size, 4);
  const auto reference = pl::run_frames(make(), frames, {.threads = 1, .fuse = false});
  for (int threads : {1, 2, 8}) {
    for (int rows : {1, 2, 3, 7, 0}) {
      const auto fused = pl::run_frames(make(), frames, {.threads = threads, .fuse = true, .fused_stripe_rows = rows});
      ASSERT_EQ(fused.size(), reference.size());
      for (size_t f = 0; f < fused.size(); ++f) {
        for (size_t k = 0; k < fused[f].outputs.size(); ++k) {
          expect_same_value(fused[f].outputs[k], reference[f].outputs[k],
                            "size " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", threads " +
                                std::to_string(threads) + ", stripe rows " + std::to_string(rows) + ", frame " +
                                std::to_string(f) + ", output " + std::to_string(k));
        }
      }
    }
  }
}

// A fusable point node that copies its input and counts the rows it computes: unfused, each row
// once; fused, a producer's rows in a consumer's halo are computed again for every stripe that needs
// them. So the count tells whether the executor really ran the fused step.
class CountingCopyNode final : public pl::Node {
 public:
  explicit CountingCopyNode(std::atomic<long>& rows)
      : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, neopipe::kernels::Footprint::point,
             pl::FrameOrder::any),
        rows_(rows) {}
  void compute_row(const pl::RowInputs& in, std::uint8_t* out, int y, int width) const override {
    std::copy_n(in.row(0, y), width, out);
    ++rows_;
  }
  bool fusable() const override { return true; }

 private:
  std::atomic<long>& rows_;
};

// A random graph of row-computable stages, as YAML: a chain from a gray source through point (lut,
// threshold), 3x3 arithmetic (conv3x3, sobel into 16 bits and back), 3x3 Boolean (bool3x3) and
// two-input stages (whose second input is any earlier node, which then has two users and stays
// whole), random parameters and borders; sometimes a blob table on the last stage.
std::string random_graph_yaml(std::mt19937& rng) {
  const auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  std::vector<std::string> names{"src"};
  std::vector<std::string> gray{"src"};  // the gray8 ones, which any stage may read
  std::string yaml = "nodes:\n  - {name: src, kernel: source, params: {format: gray}}\n";
  // A bool3x3 border value is a bit (0..1); a conv3x3 one any byte.
  const auto border = [&](int max_value) {
    return pick(2) == 0 ? std::string("border: replicate")
                        : "border: constant, border_value: " + std::to_string(pick(max_value + 1));
  };
  const auto add = [&](const std::string& kernel, const std::string& params, const std::string& inputs) {
    const std::string name = "n" + std::to_string(names.size());
    yaml += "  - {name: " + name + ", kernel: " + kernel + ", params: {" + params + "}, inputs: {" + inputs + "}}\n";
    names.push_back(name);
    if (!params.starts_with("preset: sobel")) gray.push_back(name);
  };
  const int stages = 2 + pick(7);
  for (int i = 0; i < stages; ++i) {
    const std::string in = "in: " + names.back();
    switch (pick(6)) {
      case 0: {
        static const char* const exprs[] = {"255 - a", "a / 2 + 60", "(a * 3 + 7) / 4", "a > 90 ? 200 : a"};
        add("lut", std::string("expr: \"") + exprs[pick(4)] + "\"", in);
        break;
      }
      case 1:
        add("threshold", "value: " + std::to_string(pick(255)) + ", high: " + std::to_string(1 + pick(255)), in);
        break;
      case 2: {
        static const char* const presets[] = {"identity", "smooth", "laplace", "sharpen"};
        add("conv3x3", std::string("preset: ") + presets[pick(4)] + ", " + border(255), in);
        break;
      }
      case 3:
        add("conv3x3",
            std::string("preset: ") + (pick(2) == 0 ? "sobel_x" : "sobel_y") + ", output: s16, " + border(255), in);
        add("convert", "abs: true, shift: " + std::to_string(pick(5)), "in: " + names.back());
        break;
      case 4: {
        static const char* const ops[] = {"op: erode", "op: dilate", "expr: \"c && (n + s + e + w) < 4\"",
                                          "pattern: \"x1x 111 x1x\""};
        add("bool3x3", std::string(ops[pick(4)]) + ", " + border(1), in);
        break;
      }
      default: {
        static const char* const two[] = {"add", "sub", "absdiff", "min", "max", "and", "or", "xor"};
        const std::string other = gray[static_cast<size_t>(pick(static_cast<int>(gray.size())))];
        if (pick(4) == 0) {
          add("lut2", "expr: \"(a + 3*b) / 4\"", "a: " + names.back() + ", b: " + other);
        } else {
          add(two[pick(8)], "", "a: " + names.back() + ", b: " + other);
        }
      }
    }
  }
  if (pick(3) == 0) {
    add("blobs", "threshold: " + std::to_string(pick(200)) + ", connectivity: " + (pick(2) == 0 ? "4" : "8"),
        "in: " + names[names.size() - 1] + ", weights: src");
  }
  return yaml + "outputs: [" + names.back() + "]\n";
}

}  // namespace

TEST(FusionPlan, FourStageChainFusesUpToTheBlobs) {
  EXPECT_EQ(groups_of(compile_yaml(kChain)),
            (std::vector<std::vector<std::string>>{{"smooth", "binary", "eroded", "opened"}}));
}

TEST(FusionPlan, TreesFuseIntoTheirSink) {
  EXPECT_EQ(groups_of(compile_yaml(kTree)),
            (std::vector<std::vector<std::string>>{
                {"gray", "gx", "mx", "inv", "g2", "sharp", "mix", "bin", "edge", "grown", "g3", "bin2", "out"}}));
}

TEST(FusionPlan, ExamplesFuseWhatIsUsedOnce) {
  // gray feeds the background, the difference and the blob weights, so it stays a whole image.
  EXPECT_EQ(groups_of(compile_example("background_subtraction.yaml")),
            (std::vector<std::vector<std::string>>{{"difference", "moving", "eroded", "opened"}}));
  // smooth feeds both gradients.
  EXPECT_EQ(groups_of(compile_example("edges.yaml")),
            (std::vector<std::vector<std::string>>{{"gx", "gy", "mx", "my", "magnitude"}}));
  // Otsu's threshold needs its whole input first; gray has two uses.
  EXPECT_TRUE(groups_of(compile_example("blobs.yaml")).empty());
  // excess feeds the blobs twice (image and weights), and the blobs node cannot fuse.
  EXPECT_TRUE(groups_of(compile_example("marbles.yaml")).empty());
}

TEST(FusionPlan, OutputsDelaysAndSharedNodesStayWhole) {
  // `a` is a graph output, `b` is used twice, `c` feeds a delay edge: none is absorbed.
  const auto g = compile_yaml(R"(
nodes:
  - {name: src, kernel: source, params: {format: gray}}
  - {name: a, kernel: lut, params: {expr: "a / 2"}, inputs: {in: src}}
  - {name: a2, kernel: lut, params: {expr: "a + 1"}, inputs: {in: a}}
  - {name: b, kernel: lut, params: {expr: "a / 3"}, inputs: {in: src}}
  - {name: b2, kernel: add, inputs: {a: b, b: b}}
  - {name: c, kernel: lut, params: {expr: "a / 4"}, inputs: {in: src}}
  - {name: c2, kernel: add, inputs: {a: src, b: {from: c, delay: 1}}}
outputs: [a, a2, b2, c2]
)");
  EXPECT_TRUE(groups_of(g).empty());
}

TEST(FusionPlan, OtsuThresholdIsNotFused) {
  const auto g = compile_yaml(R"(
nodes:
  - {name: src, kernel: source, params: {format: gray}}
  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: src}}
  - {name: bin, kernel: threshold, params: {value: otsu}, inputs: {in: smooth}}
  - {name: opened, kernel: bool3x3, params: {op: erode}, inputs: {in: bin}}
outputs: [opened]
)");
  // smooth is used once, by a node that cannot fuse; bin cannot fuse either.
  EXPECT_TRUE(groups_of(g).empty());
}

TEST(Fusion, ChainEqualsUnfused) {
  for (const cv::Size size : {cv::Size(61, 37), cv::Size(1, 1), cv::Size(5, 2), cv::Size(33, 1), cv::Size(1, 23)}) {
    expect_fused_equals_unfused([] { return compile_yaml(kChain); }, size);
  }
}

TEST(Fusion, TreeEqualsUnfused) {
  for (const cv::Size size : {cv::Size(47, 29), cv::Size(2, 3), cv::Size(70, 9)}) {
    expect_fused_equals_unfused([] { return compile_yaml(kTree); }, size);
  }
}

TEST(Fusion, FusedRunsReallyRunTheFusedStep) {
  // Equal outputs alone would also hold if the executor ignored `fuse`.
  std::atomic<long> rows{0};
  pl::KernelRegistry registry = pl::standard_kernels();
  registry.add({"counting_copy", "copies its input, counting the rows it computes",
                [&](pl::NodeContext&) { return std::make_unique<CountingCopyNode>(rows); }});
  const auto make = [&] {
    return compile_yaml(R"(
nodes:
  - {name: src, kernel: source, params: {format: gray}}
  - {name: copy, kernel: counting_copy, inputs: {in: src}}
  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: copy}}
outputs: [smooth]
)",
                        registry);
  };
  ASSERT_EQ(groups_of(make()), (std::vector<std::vector<std::string>>{{"copy", "smooth"}}));
  const cv::Size size(40, 20);
  const auto frames = frames_for(make(), size, 3);
  const auto unfused = pl::run_frames(make(), frames, {.threads = 2, .fuse = false});
  EXPECT_EQ(rows.load(), 3L * size.height);
  rows = 0;
  const auto fused = pl::run_frames(make(), frames, {.threads = 2, .fuse = true, .fused_stripe_rows = 1});
  // One-row stripes of smooth each need three rows of copy, two at the frame's edges.
  EXPECT_EQ(rows.load(), 3L * (3 * size.height - 2));
  ASSERT_EQ(fused.size(), unfused.size());
  for (size_t f = 0; f < fused.size(); ++f) {
    expect_same_value(fused[f].outputs[0], unfused[f].outputs[0], "frame " + std::to_string(f));
  }
}

TEST(Fusion, ExamplesEqualUnfused) {
  // The examples that have fused groups; blobs.yaml and marbles.yaml have none (FusionPlan above).
  for (const char* file : {"background_subtraction.yaml", "edges.yaml"}) {
    SCOPED_TRACE(file);
    expect_fused_equals_unfused([&] { return compile_example(file); }, {45, 31});
  }
}

TEST(Fusion, RandomGraphsEqualUnfused) {
  // Random graphs on random sizes (1-3 rows and columns among them): fused, for every stripe height
  // and thread count, bit-identical to the unfused run (whose kernels the kernel tests check against
  // scalar references).
  std::mt19937 rng(20261204);
  int compared = 0;
  for (int g = 0; g < 60; ++g) {
    const std::string yaml = random_graph_yaml(rng);
    const bool tiny = g % 3 == 0;
    const cv::Size size(1 + static_cast<int>(rng() % (tiny ? 3 : 97)), 1 + static_cast<int>(rng() % (tiny ? 3 : 40)));
    if (pl::plan_fusion(compile_yaml(yaml)).empty()) continue;  // nothing fused: nothing to compare
    SCOPED_TRACE("graph " + std::to_string(g) + " at " + std::to_string(size.width) + "x" +
                 std::to_string(size.height) + ":\n" + yaml);
    expect_fused_equals_unfused([&] { return compile_yaml(yaml); }, size);
    if (HasFatalFailure()) return;
    ++compared;
  }
  // Most random graphs have a fused group; if none had, the test would have compared nothing.
  EXPECT_GE(compared, 40);
}
