#include "pipeline/fusion.hpp"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <numeric>

namespace neopipe::pipeline {
namespace {

// Bytes a stripe's buffers may take: about a quarter of a core's L2, leaving room for the inputs.
constexpr size_t kStripeBudget = size_t{192} * 1024;

// Rows of member `pos`'s output held while the sink computes rows [r0, r1).
struct Span {
  int lo;
  int hi;
};

// The rows of a step's members during one stripe: external inputs from whole frames, internal ones
// from the stripe buffers.
class StripeRows final : public RowInputs {
 public:
  StripeRows(const std::vector<const cv::Mat*>& external, const std::vector<int>& producer_pos,
             const std::vector<std::vector<std::uint8_t>>& buffers, const std::vector<Span>& spans,
             const std::vector<size_t>& row_bytes)
      : external_(external), producer_pos_(producer_pos), buffers_(buffers), spans_(spans), row_bytes_(row_bytes) {}

  const std::uint8_t* row(size_t input, int y) const override {
    const int p = producer_pos_[input];
    if (p < 0) return external_[input]->ptr<std::uint8_t>(y);
    const auto q = static_cast<size_t>(p);
    return buffers_[q].data() + static_cast<size_t>(y - spans_[q].lo) * row_bytes_[q];
  }

 private:
  const std::vector<const cv::Mat*>& external_;
  const std::vector<int>& producer_pos_;
  const std::vector<std::vector<std::uint8_t>>& buffers_;
  const std::vector<Span>& spans_;
  const std::vector<size_t>& row_bytes_;
};

}  // namespace

std::vector<std::vector<int>> plan_fusion(const CompiledGraph& graph) {
  const auto& nodes = graph.nodes();
  const size_t n = nodes.size();
  std::vector<int> uses(n, 0);
  std::vector<int> sole_consumer(n, -1);  // the consumer of a node's only use, if that use is plain
  for (size_t c = 0; c < n; ++c) {
    for (const auto& in : nodes[c].inputs) {
      if (!in.from.valid()) continue;
      ++uses[static_cast<size_t>(in.from.node)];
      sole_consumer[static_cast<size_t>(in.from.node)] = in.delayed ? -1 : static_cast<int>(c);
      if (in.initial_from.valid()) ++uses[static_cast<size_t>(in.initial_from.node)];
    }
  }
  for (const auto& o : graph.outputs()) ++uses[static_cast<size_t>(o.node)];

  std::vector<int> into(n, -1);  // the consumer a node is absorbed into
  for (size_t p = 0; p < n; ++p) {
    const Node& node = *nodes[p].impl;
    const int c = sole_consumer[p];
    if (static_cast<int>(p) == graph.source() || !node.fusable() || node.outputs().size() != 1 || uses[p] != 1 ||
        c < 0 || !nodes[static_cast<size_t>(c)].impl->fusable()) {
      continue;
    }
    into[p] = c;
  }
  std::map<int, std::vector<int>> groups;  // by sink
  for (size_t p = 0; p < n; ++p) {
    if (into[p] < 0) continue;
    int sink = into[p];
    while (into[static_cast<size_t>(sink)] >= 0) sink = into[static_cast<size_t>(sink)];
    groups[sink].push_back(static_cast<int>(p));
  }
  std::vector<std::vector<int>> out;
  for (auto& [sink, members] : groups) {
    members.push_back(sink);
    std::sort(members.begin(), members.end());  // node indices are already topological
    out.push_back(std::move(members));
  }
  return out;
}

FusedStep::FusedStep(const CompiledGraph& graph, std::vector<int> members) : members_(std::move(members)) {
  const auto& nodes = graph.nodes();
  std::map<int, int> pos_of;
  for (size_t pos = 0; pos < members_.size(); ++pos) pos_of[members_[pos]] = static_cast<int>(pos);
  producer_pos_.resize(members_.size());
  halo_.assign(members_.size(), 0);
  pixel_bytes_.resize(members_.size());
  for (size_t pos = 0; pos < members_.size(); ++pos) {
    const CompiledNode& node = nodes[static_cast<size_t>(members_[pos])];
    pixel_bytes_[pos] = cv::Mat(1, 1, cv_type(node.impl->outputs()[0].type)).elemSize();
    for (const auto& in : node.inputs) {
      const auto it = in.from.valid() && !in.delayed ? pos_of.find(in.from.node) : pos_of.end();
      producer_pos_[pos].push_back(it == pos_of.end() ? -1 : it->second);
    }
  }
  // Walk from the sink back: a producer must cover its consumer's rows plus the consumer's halo.
  for (size_t pos = members_.size(); pos-- > 0;) {
    const int reach = halo_[pos] + kernels::halo_rows(nodes[static_cast<size_t>(members_[pos])].impl->footprint());
    for (const int p : producer_pos_[pos]) {
      if (p >= 0) halo_[static_cast<size_t>(p)] = std::max(halo_[static_cast<size_t>(p)], reach);
    }
  }
}

bool FusedStep::internal(int member, size_t k) const {
  const auto it = std::find(members_.begin(), members_.end(), member);
  return it != members_.end() && producer_pos_[static_cast<size_t>(it - members_.begin())][k] >= 0;
}

void FusedStep::configure(cv::Size frame, int rows) {
  frame_ = frame;
  if (rows > 0) {
    stripe_rows_ = rows;
    return;
  }
  size_t bytes_per_row = 0;
  for (size_t pos = 0; pos + 1 < members_.size(); ++pos)
    bytes_per_row += pixel_bytes_[pos] * static_cast<size_t>(frame.width);
  const int max_halo = *std::max_element(halo_.begin(), halo_.end());
  // Tall enough that recomputing the halo rows at each stripe's edges costs little, short enough to
  // stay in cache.
  const int budget_rows = static_cast<int>(kStripeBudget / std::max<size_t>(bytes_per_row, 1));
  stripe_rows_ = std::clamp(budget_rows, std::max(8, 8 * max_halo), std::max(frame.height, 1));
}

void FusedStep::run(const CompiledGraph& graph, const std::function<const cv::Mat&(size_t, size_t)>& external,
                    cv::Mat& out, bool parallel) {
  const auto& nodes = graph.nodes();
  const size_t m = members_.size();
  std::vector<std::vector<const cv::Mat*>> ext(m);
  std::vector<size_t> row_bytes(m);
  for (size_t pos = 0; pos < m; ++pos) {
    row_bytes[pos] = pixel_bytes_[pos] * static_cast<size_t>(frame_.width);
    for (size_t k = 0; k < producer_pos_[pos].size(); ++k) {
      ext[pos].push_back(producer_pos_[pos][k] < 0 ? &external(pos, k) : nullptr);
    }
  }
  const int h = frame_.height;
  const int w = frame_.width;
  const int stripes = (h + stripe_rows_ - 1) / stripe_rows_;
  const auto stripe = [&](int s) {
    const int r0 = s * stripe_rows_;
    const int r1 = std::min(h, r0 + stripe_rows_);
    auto& buffers = scratch_.local();
    buffers.resize(m);
    std::vector<Span> spans(m);
    for (size_t pos = 0; pos < m; ++pos) {
      spans[pos] = {std::max(0, r0 - halo_[pos]), std::min(h, r1 + halo_[pos])};
      if (pos + 1 < m) buffers[pos].resize(static_cast<size_t>(spans[pos].hi - spans[pos].lo) * row_bytes[pos]);
    }
    for (size_t pos = 0; pos < m; ++pos) {
      const Node& node = *nodes[static_cast<size_t>(members_[pos])].impl;
      const StripeRows in(ext[pos], producer_pos_[pos], buffers, spans, row_bytes);
      const bool sink = pos + 1 == m;
      for (int y = spans[pos].lo; y < spans[pos].hi; ++y) {
        std::uint8_t* dst = sink ? out.ptr<std::uint8_t>(y)
                                 : buffers[pos].data() + static_cast<size_t>(y - spans[pos].lo) * row_bytes[pos];
        node.compute_row(in, dst, y, w);
      }
    }
  };
  if (parallel && stripes > 1) {
    tbb::parallel_for(0, stripes, stripe);
  } else {
    for (int s = 0; s < stripes; ++s) stripe(s);
  }
}

}  // namespace neopipe::pipeline
