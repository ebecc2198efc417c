#include "pipeline/builtin_graphs.hpp"

#include <string>

namespace neopipe::pipeline {

GraphSpec blob_graph(const BlobGraphOptions& o) {
  GraphBuilder b("<built-in blob graph>");
  const bool bgr = o.source == PortType::bgr8;
  b.node("src", "source", bgr ? "{format: bgr}" : "{format: gray}");
  std::string gray = "src";
  if (bgr) {
    b.node("gray", "gray").connect("src", "gray.in");
    gray = "gray";
  }
  b.node("binary", "threshold", "{value: " + (o.threshold ? std::to_string(*o.threshold) : std::string("otsu")) + "}");
  b.node("blobs", "blobs", "{threshold: 0, connectivity: " + std::to_string(o.connectivity) + "}");
  b.connect(gray, "binary.in").connect("binary", "blobs.in").connect(gray, "blobs.weights");
  b.output("blobs");
  return b.spec();
}

GraphSpec marble_graph(int workspace_level) {
  GraphBuilder b("<built-in marble graph>");
  b.node("src", "source", "{format: gray}");
  b.node("excess", "lut", "{expr: \"a - " + std::to_string(workspace_level) + "\"}");
  b.node("blobs", "blobs", "{threshold: 0, connectivity: 8}");
  b.connect("src", "excess.in").connect("excess", "blobs.in").connect("excess", "blobs.weights");
  b.output("blobs");
  return b.spec();
}

GraphSpec panorama_graph() {
  GraphBuilder b("<built-in panorama graph>");
  b.node("src", "source", "{format: s16}");
  b.node("blobs", "value_blobs", "{connectivity: 8}");
  b.connect("src", "blobs.in");
  b.output("blobs");
  return b.spec();
}

}  // namespace neopipe::pipeline
