// The navigator's eye: the engine's built-in blob graph run on one onboard frame at a time, its
// centroids turned into window coordinates. The navigator needs each sighting before it can decide
// its next move, so there is never a second frame to overlap with: the compiled graph's nodes run
// in order on the calling thread, as the executor would run them for a lone frame, without its
// worker threads (and without the process-wide thread limit it sets while it lives).

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

#include "nav/navigator/navigator.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/node.hpp"

namespace neopipe::nav::navigator {
namespace {

pipeline::CompiledGraph gray_blob_graph() {
  pipeline::BlobGraphOptions options;
  options.source = pipeline::PortType::gray8;
  pipeline::CompiledGraph graph = pipeline::compile(pipeline::blob_graph(options), pipeline::standard_kernels());
  // Each sighting stands alone: a delayed edge would make a look depend on the one before.
  if (graph.has_delays()) throw std::logic_error("the navigator's blob graph must not have delays");
  return graph;
}

// The workspace's gray level: the median of a sparse grid of pixels. Marbles cover a small part of
// any window, so the median is the bare plane whatever the illumination gradient.
int background_level(const cv::Mat& gray) {
  std::array<int, 256> histogram{};
  int count = 0;
  constexpr int stride = 7;
  for (int y = stride / 2; y < gray.rows; y += stride) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    for (int x = stride / 2; x < gray.cols; x += stride) {
      ++histogram[row[x]];
      ++count;
    }
  }
  int seen = 0;
  for (int v = 0; v < 256; ++v) {
    seen += histogram[static_cast<std::size_t>(v)];
    if (2 * seen >= count) return v;
  }
  return 255;
}

}  // namespace

struct Eye::Impl {
  Impl(pipeline::io::FrameSource& camera, const NavigatorConfig& navigator)
      : source(camera),
        config(navigator),
        graph(gray_blob_graph()),
        blobs(*graph.find_output(pipeline::PortType::blobs)) {
    values.resize(graph.nodes().size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i].resize(graph.nodes()[i].impl->outputs().size());
  }

  void configure(cv::Size size) {
    for (auto& node : graph.nodes()) node.impl->configure(size);
    size_ = size;
  }

  const pipeline::BlobList& run(const cv::Mat& frame) {
    if (frame.type() != CV_8UC1) throw std::runtime_error("the navigator's eye takes gray frames (CV_8UC1)");
    if (frame.size() != size_) configure(frame.size());
    const auto src = static_cast<std::size_t>(graph.source());
    values[src][0] = frame;
    std::vector<const pipeline::Value*> inputs;
    std::vector<pipeline::Value*> outputs;
    for (std::size_t i = 0; i < graph.nodes().size(); ++i) {
      if (i == src) continue;
      pipeline::CompiledNode& node = graph.nodes()[i];
      inputs.assign(node.inputs.size(), nullptr);
      for (std::size_t k = 0; k < node.inputs.size(); ++k) {
        const pipeline::PortAddress from = node.inputs[k].from;
        if (from.valid()) inputs[k] = &values[static_cast<std::size_t>(from.node)][static_cast<std::size_t>(from.port)];
      }
      outputs.clear();
      for (pipeline::Value& v : values[i]) outputs.push_back(&v);
      pipeline::NodeIO io(inputs, outputs, node.impl->outputs(), size_);
      node.impl->begin_frame(io);
      if (node.impl->footprint() != kernels::Footprint::frame) node.impl->run_rows(io, {0, size_.height});
    }
    const pipeline::PortAddress out = graph.outputs()[blobs];
    return std::get<pipeline::BlobList>(values[static_cast<std::size_t>(out.node)][static_cast<std::size_t>(out.port)]);
  }

  pipeline::io::FrameSource& source;
  NavigatorConfig config;
  pipeline::CompiledGraph graph;
  std::size_t blobs;
  std::vector<std::vector<pipeline::Value>> values;  // [node][output port], reused frame to frame
  cv::Size size_;
  pipeline::io::SourceFrame last;
  std::int64_t frames = 0;
};

Eye::Eye(pipeline::io::FrameSource& source, const NavigatorConfig& config)
    : impl_(std::make_unique<Impl>(source, config)) {}
Eye::~Eye() = default;

const pipeline::io::SourceFrame& Eye::last_frame() const {
  return impl_->last;
}

Sighting Eye::look() {
  Impl& eye = *impl_;
  std::optional<pipeline::io::SourceFrame> frame = eye.source.next();
  if (!frame) throw std::runtime_error("the onboard camera (" + eye.source.description() + ") has no more frames");
  eye.last = std::move(*frame);
  const cv::Mat& image = eye.last.image;
  const pipeline::BlobList& blobs = eye.run(image);

  const double a = eye.config.window.side;
  const double mm_per_px_x = a / image.cols;
  const double mm_per_px_y = a / image.rows;
  const double radius_px = 0.5 * eye.config.camera.object_diameter / mm_per_px_x;
  const int background = background_level(image);

  Sighting s;
  s.frame = eye.frames++;
  for (const kernels::Blob& b : blobs) {
    if (b.area < eye.config.camera.min_blob_area) continue;
    const int u = std::clamp(static_cast<int>(b.cx), 0, image.cols - 1);
    const int v = std::clamp(static_cast<int>(b.cy), 0, image.rows - 1);
    if (image.at<std::uint8_t>(v, u) < background + eye.config.camera.min_contrast) continue;
    // Pixel centres are at (u + 0.5, v + 0.5). A blob cut by a border is a cap of its marble: along
    // that axis the marble's centre lies one radius in from the cap's far edge.
    double cx = b.cx + 0.5;
    double cy = b.cy + 0.5;
    const bool west = b.x0 == 0;
    const bool east = b.x0 + b.width == image.cols;
    const bool south = b.y0 + b.height == image.rows;
    const bool north = b.y0 == 0;
    if (west != east) cx = west ? b.x0 + b.width - radius_px : b.x0 + radius_px;
    if (north != south) cy = north ? b.y0 + b.height - radius_px : b.y0 + radius_px;
    const Eigen::Vector2d p(cx * mm_per_px_x, a - cy * mm_per_px_y);
    // Visible means the centre strictly inside the window (park-kender.md §2), as the map-maker
    // assumed: a cap whose marble's centre lies outside is not an object in view.
    if (p.x() > 0 && p.x() < a && p.y() > 0 && p.y() < a) s.objects.push_back(p);
  }
  return s;
}

}  // namespace neopipe::nav::navigator
