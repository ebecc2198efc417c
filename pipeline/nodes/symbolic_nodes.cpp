// Iconic-to-symbolic nodes: whole frames in, tables out.

#include "kernels/blobs.hpp"
#include "kernels/histogram.hpp"
#include "kernels/threshold.hpp"
#include "kernels/value_blobs.hpp"
#include "pipeline/nodes/nodes.hpp"
#include "pipeline/striped_blobs.hpp"

namespace neopipe::pipeline::nodes {
namespace {

using kernels::Footprint;

class HistogramNode final : public Node {
 public:
  HistogramNode()
      : Node({{"in", PortType::gray8}}, {{"out", PortType::histogram}}, Footprint::frame, FrameOrder::any) {}
  void begin_frame(NodeIO& io) override {
    auto& h = io.out<Histogram>(0);
    h.fill(0);
    kernels::accumulate_histogram(io.image(0), h);
  }
};

class BlobsNode final : public Node {
 public:
  BlobsNode(kernels::BlobParams params, bool otsu)
      : Node({{"in", PortType::gray8}, {"weights", PortType::gray8, true}}, {{"out", PortType::blobs}},
             Footprint::frame, FrameOrder::any),
        params_(params),
        otsu_(otsu) {}
  void begin_frame(NodeIO& io) override {
    const cv::Mat& in = io.image(0);
    kernels::BlobParams p = params_;
    if (otsu_) p.threshold = kernels::otsu_threshold(kernels::histogram(in));
    const cv::Mat weights = io.connected(1) ? io.image(1) : cv::Mat();
    io.out<BlobList>(0) = striped_blobs(in, p, weights);
  }

 private:
  kernels::BlobParams params_;
  bool otsu_;
};

// The blob kernel's s16 mode: components of equal non-zero value. Whole frames only: the ring
// images it is made for (320 rows) are below the height the gray blobs node would cut into stripes,
// and other frames in flight keep the executor's threads busy.
class ValueBlobsNode final : public Node {
 public:
  explicit ValueBlobsNode(kernels::Connectivity connectivity)
      : Node({{"in", PortType::s16}}, {{"out", PortType::blobs}}, Footprint::frame, FrameOrder::any),
        connectivity_(connectivity) {}
  void begin_frame(NodeIO& io) override {
    io.out<BlobList>(0) = kernels::extract_value_blobs(io.image(0), connectivity_);
  }

 private:
  kernels::Connectivity connectivity_;
};

kernels::Connectivity connectivity_param(NodeContext& c) {
  const int conn = c.params.get_int("connectivity", 8, 4, 8);
  if (conn != 4 && conn != 8) c.params.fail("connectivity", "must be 4 or 8");
  return conn == 4 ? kernels::Connectivity::four : kernels::Connectivity::eight;
}

}  // namespace

void register_symbolic_nodes(KernelRegistry& r) {
  r.add({"histogram", "256-bin histogram of a gray8 image",
         [](NodeContext&) { return std::make_unique<HistogramNode>(); }});
  r.add({"blobs",
         "connected components of in > threshold with area, box, centroid, weighted centroid (weights input, default "
         "in) and central moments; params: threshold (-1..255 or otsu, default 0), connectivity (4 | 8, default 8)",
         [](NodeContext& c) {
           kernels::BlobParams p;
           const bool otsu = c.params.get_string("threshold", "0") == "otsu";
           p.threshold = otsu ? 0 : c.params.get_int("threshold", 0, -1, 255);
           p.connectivity = connectivity_param(c);
           return std::make_unique<BlobsNode>(p, otsu);
         }});
  r.add({"value_blobs",
         "the blob kernel's s16 mode: connected components of equal non-zero value (0 is background; touching "
         "regions of different values stay apart), each with its value, area, box, centroid and central moments; "
         "params: connectivity (4 | 8, default 8)",
         [](NodeContext& c) { return std::make_unique<ValueBlobsNode>(connectivity_param(c)); }});
}

}  // namespace neopipe::pipeline::nodes
