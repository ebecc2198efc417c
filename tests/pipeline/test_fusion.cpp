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
