#include "pipeline/inline_runner.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "pipeline/frame_size.hpp"
#include "pipeline/source_location.hpp"

namespace neopipe::pipeline {
namespace {

// A copy that the producer's next frame cannot overwrite: nodes write their images in place.
Value deep_copy(const Value& v) {
  if (const auto* m = std::get_if<cv::Mat>(&v)) return m->clone();
  return v;
}

}  // namespace

InlineRunner::InlineRunner(CompiledGraph graph) : graph_(std::move(graph)) {
  const auto& nodes = graph_.nodes();
  values_.resize(nodes.size());
  previous_.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    values_[i].resize(nodes[i].impl->outputs().size());
    previous_[i].resize(nodes[i].inputs.size());
  }
}

void InlineRunner::configure(cv::Size size) {
  for (auto& n : graph_.nodes()) {
    try {
      n.impl->configure(size);
    } catch (const std::invalid_argument& e) {
      throw GraphError(n.where, "node '" + n.name + "': " + e.what());
    }
  }
  // First-frame values of delayed inputs that start from a constant.
  for (std::size_t i = 0; i < graph_.nodes().size(); ++i) {
    const auto& node = graph_.nodes()[i];
    for (std::size_t k = 0; k < node.inputs.size(); ++k) {
      const CompiledInput& in = node.inputs[k];
      if (in.delayed && !in.initial_from.valid()) {
        previous_[i][k] = constant_value(graph_.type_of(in.from), size, in.initial_fill);
      }
    }
  }
  size_ = size;
}

const Value* InlineRunner::input_value(std::size_t node, std::size_t input) const {
  const CompiledInput& in = graph_.nodes()[node].inputs[input];
  if (!in.from.valid()) return nullptr;
  const auto at = [this](PortAddress a) {
    return &values_[static_cast<std::size_t>(a.node)][static_cast<std::size_t>(a.port)];
  };
  if (!in.delayed) return at(in.from);
  // The first frame reads the initial port of this frame (compiled to run before this node).
  if (frames_ == 0 && in.initial_from.valid()) return at(in.initial_from);
  return &previous_[node][input];
}

const std::vector<Value>& InlineRunner::run(const cv::Mat& frame) {
  const int want = cv_type(graph_.source_type());
  if (frame.empty() || frame.type() != want) {
    throw std::invalid_argument("the graph's source takes " + std::string(to_string(graph_.source_type())) + " (" +
                                cv::typeToString(want) + ") images, got " +
                                (frame.empty() ? std::string("an empty one") : cv::typeToString(frame.type())));
  }
  if (frames_ == 0) {
    configure(frame.size());
  } else if (frame.size() != size_) {
    throw std::invalid_argument("frame " + std::to_string(frames_) + " is " + size_text(frame.size()) +
                                " but the first was " + size_text(size_));
  }
  const auto src = static_cast<std::size_t>(graph_.source());
  values_[src][0] = frame;
  std::vector<const Value*> inputs;
  std::vector<Value*> outputs;
  for (std::size_t i = 0; i < graph_.nodes().size(); ++i) {
    if (i == src) continue;
    CompiledNode& node = graph_.nodes()[i];
    inputs.assign(node.inputs.size(), nullptr);
    for (std::size_t k = 0; k < node.inputs.size(); ++k) inputs[k] = input_value(i, k);
    outputs.clear();
    for (Value& v : values_[i]) outputs.push_back(&v);
    NodeIO io(inputs, outputs, node.impl->outputs(), size_);
    node.impl->begin_frame(io);
    if (node.impl->footprint() != kernels::Footprint::frame) node.impl->run_rows(io, {0, size_.height});
  }
  if (graph_.has_delays()) {
    for (std::size_t i = 0; i < graph_.nodes().size(); ++i) {
      const auto& node = graph_.nodes()[i];
      for (std::size_t k = 0; k < node.inputs.size(); ++k) {
        const CompiledInput& in = node.inputs[k];
        if (in.delayed) {
          previous_[i][k] =
              deep_copy(values_[static_cast<std::size_t>(in.from.node)][static_cast<std::size_t>(in.from.port)]);
        }
      }
    }
  }
  // Assigned in place, so a blob table's copy reuses last frame's memory.
  const auto& declared = graph_.outputs();
  outputs_.resize(declared.size());
  for (std::size_t j = 0; j < declared.size(); ++j) {
    outputs_[j] = values_[static_cast<std::size_t>(declared[j].node)][static_cast<std::size_t>(declared[j].port)];
  }
  ++frames_;
  return outputs_;
}

}  // namespace neopipe::pipeline
