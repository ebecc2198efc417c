// The threshold -> blobs folding pass (pipeline/threshold_folding.hpp): which pairs fold, which
// must not, and that a folded graph gives exactly the blob table of the graph as declared.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/threshold_folding.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)

namespace {

std::vector<std::string> node_names(const pl::CompiledGraph& g) {
  std::vector<std::string> names;
  for (const auto& n : g.nodes()) names.push_back(n.name);
  return names;
}

// A gray source, a threshold and a blob node; `threshold`, `blobs` and `extra` are spliced in.
std::string graph(const std::string& threshold, const std::string& blobs, const std::string& extra = "",
                  const std::string& outputs = "[blobs]") {
  return "nodes:\n"
         "  - {name: src, kernel: source, params: {format: gray}}\n"
         "  - {name: binary, kernel: threshold, " +
         threshold + "}\n  - {name: blobs, kernel: blobs, " + blobs + "}\n" + extra + "outputs: " + outputs + "\n";
}

// Frames with something at every gray level, in blobs of every shape.
std::vector<cv::Mat> frames() {
  std::vector<cv::Mat> out;
  cv::RNG rng(5);
  for (int i = 0; i < 3; ++i) {
    cv::Mat f(61, 83, CV_8UC1);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(f, f, {7, 7}, 2.0);
    cv::normalize(f, f, 0, 255, cv::NORM_MINMAX);
    out.push_back(f);
  }
  return out;
}

void expect_same_tables(const std::string& yaml) {
  const pl::GraphSpec spec = pl::parse_graph_spec(yaml, "spec.yaml");
  const auto fs = frames();
  const auto folded = pl::run_frames(pl::compile(spec, pl::standard_kernels()), fs);
  const auto declared = pl::run_frames(pl::compile_as_declared(spec, pl::standard_kernels()), fs);
  ASSERT_EQ(folded.size(), declared.size());
  for (size_t f = 0; f < folded.size(); ++f) {
    expect_same_blobs(std::get<pl::BlobList>(folded[f].outputs.at(0)),
                      std::get<pl::BlobList>(declared[f].outputs.at(0)), "frame " + std::to_string(f));
  }
}

}  // namespace

TEST(ThresholdFolding, BuiltInBlobGraphFoldsAFixedThreshold) {
  const pl::GraphSpec fixed = pl::blob_graph({.threshold = 128});
  EXPECT_EQ(node_names(pl::compile(fixed, pl::standard_kernels())), (std::vector<std::string>{"src", "gray", "blobs"}));
  EXPECT_EQ(node_names(pl::compile_as_declared(fixed, pl::standard_kernels())),
            (std::vector<std::string>{"src", "gray", "binary", "blobs"}));
  EXPECT_EQ(node_names(pl::compile(fixed, pl::standard_kernels(), {.fold_thresholds = false})),
            (std::vector<std::string>{"src", "gray", "binary", "blobs"}));
  // Otsu's threshold (the default) folds too: blobs picks the same T from the same histogram.
  EXPECT_EQ(node_names(pl::compile(pl::blob_graph(), pl::standard_kernels())),
            (std::vector<std::string>{"src", "gray", "blobs"}));
}

TEST(ThresholdFolding, FoldedTablesEqualDeclaredOnesForEveryThresholdAndConnectivity) {
  for (const char* value : {"-1", "0", "1", "100", "128", "254", "255"}) {
    for (const char* high : {"1", "200", "255"}) {
      for (const char* conn : {"4", "8"}) {
        for (const char* t : {"0", "high-1"}) {
          const std::string blob_t = std::string(t) == "0" ? "0" : std::to_string(std::stoi(high) - 1);
          SCOPED_TRACE(std::string("value ") + value + ", high " + high + ", connectivity " + conn +
                       ", blob threshold " + blob_t);
          const std::string yaml = graph(
              std::string("params: {value: ") + value + ", high: " + high + "}, inputs: {in: src}",
              "params: {threshold: " + blob_t + ", connectivity: " + conn + "}, inputs: {in: binary, weights: src}");
          ASSERT_EQ(pl::compile(pl::parse_graph_spec(yaml, "spec.yaml"), pl::standard_kernels()).nodes().size(), 2U);
          expect_same_tables(yaml);
        }
      }
    }
  }
}

TEST(ThresholdFolding, OtsuThresholdsFoldIntoBlobsChoosingOtsu) {
  for (const char* threshold : {"params: {value: otsu}, inputs: {in: src}", "inputs: {in: src}",
                                "params: {value: otsu, high: 7}, inputs: {in: src}"}) {
    for (const char* blobs : {"inputs: {in: binary, weights: src}",
                              "params: {threshold: 6, connectivity: 4}, inputs: {in: binary, weights: src}"}) {
      SCOPED_TRACE(std::string(threshold) + " / " + blobs);
      const std::string yaml = graph(threshold, blobs);
      const auto folded = pl::fold_thresholds_into_blobs(pl::parse_graph_spec(yaml, "spec.yaml"));
      ASSERT_TRUE(folded.has_value());
      ASSERT_EQ(folded->nodes.size(), 2U);
      EXPECT_EQ(folded->nodes[1].params["threshold"].as<std::string>(), "otsu");
      expect_same_tables(yaml);
    }
  }
}

TEST(ThresholdFolding, PairsThatMeanSomethingElseDoNotFold) {
  const std::string blobs_in = "inputs: {in: binary, weights: src}";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"without weights, the weights would change from binary to gray",
       graph("params: {value: 100}, inputs: {in: src}", "inputs: {in: binary}")},
      {"blobs' threshold at high keeps nothing",
       graph("params: {value: 100, high: 200}, inputs: {in: src}", "params: {threshold: 200}, " + blobs_in)},
      {"blobs' threshold -1 keeps everything",
       graph("params: {value: 100}, inputs: {in: src}", "params: {threshold: -1}, " + blobs_in)},
      {"blobs' Otsu threshold is chosen on the binary image",
       graph("params: {value: 100}, inputs: {in: src}", "params: {threshold: otsu}, " + blobs_in)},
      {"the binary image is also an output",
       graph("params: {value: 100}, inputs: {in: src}", blobs_in, "", "[blobs, binary]")},
      {"the binary image has a second reader",
       graph("params: {value: 100}, inputs: {in: src}", blobs_in,
             "  - {name: inv, kernel: lut, params: {expr: \"255 - a\"}, inputs: {in: binary}}\n", "[blobs, inv]")},
      {"blobs reads the binary image of the previous frame",
       graph("params: {value: 100}, inputs: {in: src}", "inputs: {in: {from: binary, delay: 1}, weights: src}")},
      {"the threshold reads the previous frame",
       graph("params: {value: 100}, inputs: {in: {from: src, delay: 1}}", blobs_in)},
  };
  for (const auto& [why, yaml] : cases) {
    SCOPED_TRACE(why);
    const pl::GraphSpec spec = pl::parse_graph_spec(yaml, "spec.yaml");
    EXPECT_FALSE(pl::fold_thresholds_into_blobs(spec).has_value());
    EXPECT_EQ(pl::compile(spec, pl::standard_kernels()).nodes().size(),
              pl::compile_as_declared(spec, pl::standard_kernels()).nodes().size());
    expect_same_tables(yaml);
  }
}

TEST(ThresholdFolding, ErrorsSpeakOfTheGraphAsDeclared) {
  // A mistake elsewhere in a foldable graph is reported as written, not about a rewritten graph.
  const std::string yaml = graph("params: {value: 100}, inputs: {in: src}", "inputs: {in: binary, weights: nowhere}");
  try {
    (void)pl::compile(pl::parse_graph_spec(yaml, "spec.yaml"), pl::standard_kernels());
    FAIL() << "expected a GraphError";
  } catch (const pl::GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere"), std::string::npos) << e.what();
  }
}

TEST(ThresholdFolding, AMistakeInTheFoldedThresholdIsStillReported) {
  // Folding would remove the threshold node, and its bad parameter with it: compile() must not.
  const std::string yaml =
      graph("params: {value: 100, high: 999}, inputs: {in: src}", "inputs: {in: binary, weights: src}");
  EXPECT_THROW((void)pl::compile(pl::parse_graph_spec(yaml, "spec.yaml"), pl::standard_kernels()), pl::GraphError);
}
