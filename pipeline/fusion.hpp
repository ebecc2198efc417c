#pragma once
// Fusion: chains of point and 3x3 nodes run stripe by stripe as one step, PIPE-style. Only the
// chain's last node (its sink) writes a whole-frame image; every other member writes a few rows at a
// time into a small buffer that its consumer reads at once, so intermediate images never exist whole
// and stay in cache. Which nodes fuse follows from their footprints and uses alone: results are
// identical to running the nodes one by one.

#include <oneapi/tbb/enumerable_thread_specific.h>

#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "pipeline/compiled_graph.hpp"

namespace neopipe::pipeline {

/// The fused groups of a graph: each a list of node indices in topological order, the sink last,
/// at least two nodes. A node joins its consumer's group when both can compute rows alone
/// (Node::fusable), the node has one output and that output has exactly one use (a non-delayed input
/// of the consumer; not a graph output, not read by a delay edge).
std::vector<std::vector<int>> plan_fusion(const CompiledGraph& graph);

class FusedStep {
 public:
  /// `members`: one group from plan_fusion.
  FusedStep(const CompiledGraph& graph, std::vector<int> members);

  const std::vector<int>& members() const { return members_; }
  int sink() const { return members_.back(); }
  /// True if the input `k` of member `m` (a node index) comes from inside the step.
  bool internal(int member, size_t k) const;

  /// Picks the stripe height for this frame size: `rows` if given, else so that a stripe's buffers
  /// fit in a core's L2 cache.
  void configure(cv::Size frame, int rows = 0);
  int stripe_rows() const { return stripe_rows_; }

  /// Runs the step on one frame. `external(pos, k)` is the whole-frame image that feeds input k of
  /// members()[pos] from outside the step; `out` is the sink's output image, already allocated.
  /// Stripes run in parallel (tbb::parallel_for) when `parallel`.
  void run(const CompiledGraph& graph, const std::function<const cv::Mat&(size_t pos, size_t k)>& external,
           cv::Mat& out, bool parallel);

 private:
  std::vector<int> members_;
  std::vector<std::vector<int>> producer_pos_;  // [pos][k]: position of the member feeding it, or -1
  std::vector<int> halo_;                       // [pos]: rows needed beyond the sink's stripe, each side
  std::vector<size_t> pixel_bytes_;             // [pos]: bytes per pixel of the member's output
  cv::Size frame_;
  int stripe_rows_ = 0;
  tbb::enumerable_thread_specific<std::vector<std::vector<std::uint8_t>>> scratch_;
};

}  // namespace neopipe::pipeline
