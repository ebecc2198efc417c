// A program of one's own that uses the installed neopipe package (examples/consumer/CMakeLists.txt):
// it declares the blob graph in C++, runs it on frames it made itself, and prints the blobs.
//
//   blob_consumer
// prints one line per blob of each frame: "frame blob area cx cy".

#include <cstdint>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "neopipe_version.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/value.hpp"

namespace {

namespace np = neopipe::pipeline;

// Three bright discs on a dark background, at centres the blobs' centroids must reproduce.
cv::Mat make_frame() {
  cv::Mat frame(240, 320, CV_8UC1, cv::Scalar(10));
  for (const cv::Point c : {cv::Point(60, 50), cv::Point(200, 120), cv::Point(120, 190)}) {
    cv::circle(frame, c, 12, cv::Scalar(230), cv::FILLED);
  }
  return frame;
}

void print_blobs(int frame, const np::BlobList& blobs) {
  for (std::size_t i = 0; i < blobs.size(); ++i) {
    const auto& b = blobs[i];
    std::printf("%d %zu %lld %.2f %.2f\n", frame, i, static_cast<long long>(b.area), b.cx, b.cy);
  }
}

}  // namespace

int main() {
  std::printf("neopipe %s\n", neopipe::version);

  // The graph, declared in C++ as a YAML file would declare it: gray frames, a fixed threshold, blobs.
  np::GraphBuilder builder("<consumer graph>");
  builder.node("src", "source", "{format: gray}")
      .node("binary", "threshold", "{value: 128}")
      .node("blobs", "blobs", "{threshold: 0, connectivity: 8}")
      .connect("src", "binary.in")
      .connect("binary", "blobs.in")
      .output("blobs");
  // The registry must outlive the compiled graph (it holds pointers into it).
  const np::KernelRegistry kernels = np::standard_kernels();
  np::InlineRunner runner(np::compile(builder.spec(), kernels));

  // Frame 0: a cv::Mat the program owns.
  const cv::Mat frame = make_frame();
  print_blobs(0, std::get<np::BlobList>(runner.run(frame).at(0)));

  // Frame 1: the same picture in a raw buffer with a stride wider than a row (as a camera driver
  // may hand it over), wrapped without a copy.
  const std::size_t stride = 384;
  std::vector<std::uint8_t> buffer(stride * static_cast<std::size_t>(frame.rows), 0);
  for (int y = 0; y < frame.rows; ++y) {
    std::copy(frame.ptr<std::uint8_t>(y), frame.ptr<std::uint8_t>(y) + frame.cols, buffer.data() + stride * y);
  }
  const cv::Mat wrapped(frame.rows, frame.cols, CV_8UC1, buffer.data(), stride);
  print_blobs(1, std::get<np::BlobList>(runner.run(wrapped).at(0)));
  return 0;
}
