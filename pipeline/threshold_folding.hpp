#pragma once
// A compile pass: a threshold whose only reader is a blob node's `in` folds into that node.
// blobs then thresholds while it scans for runs, so the binary image is never written nor read
// again: one pass over the frame instead of three. The blob table is identical either way.

#include <optional>

#include "pipeline/graph_spec.hpp"

namespace neopipe::pipeline {

/// The spec with every foldable threshold -> blobs pair folded, or nullopt when there is none. A
/// pair folds when the threshold's output feeds only blobs.in (not delayed, not an output, not an
/// initial value), blobs' own threshold t is a number with 0 <= t < high (so "binary > t" means
/// exactly "in > T"), and blobs.weights is connected (else the weights would change from the binary
/// image to the gray one). The threshold's T may be fixed or Otsu's: blobs chooses Otsu's T the same
/// way, from the histogram of the same input. Expects a spec that compiles.
std::optional<GraphSpec> fold_thresholds_into_blobs(const GraphSpec& spec);

}  // namespace neopipe::pipeline
