#pragma once
// The union-find forest behind run-based labelling, shared by blob extraction on thresholded gray
// images (blobs.cpp) and on equal values of s16 images (value_blobs.cpp). Internal to the kernels
// library.

#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

#include "kernels/blobs.hpp"

namespace neopipe::kernels::detail {

// Provisional labels are created in raster order of the run that starts them, and a component's
// first run always starts a new label (nothing above it can belong to it). Keeping the smaller label
// as the root on every union therefore makes each root its component's raster-first label, and
// keeps parent <= label everywhere, which lets number_components fold the forest in one pass.
//
// Each label sums the runs it was given, not its root's: a run that touches a single run above
// takes that run's label without a find, and the sums meet their root once, at the end.
class LabelForest {
 public:
  LabelForest() = default;
  /// A forest of singletons with the given sums (the pieces of stripes).
  explicit LabelForest(std::vector<BlobMoments> moments) : moments_(std::move(moments)) {
    parent_.resize(moments_.size());
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  int create() {
    const int label = static_cast<int>(parent_.size());
    parent_.push_back(label);
    moments_.emplace_back();
    return label;
  }

  int find(int label) {
    // Path halving: one pass, and parent <= label still holds.
    while (parent_[idx(label)] != label) {
      const int grandparent = parent_[idx(parent_[idx(label)])];
      parent_[idx(label)] = grandparent;
      label = grandparent;
    }
    return label;
  }

  /// Joins the trees of two roots; returns the surviving root.
  int unite(int a, int b) {
    if (b < a) std::swap(a, b);
    parent_[idx(b)] = a;
    return a;
  }

  BlobMoments& moments(int label) { return moments_[idx(label)]; }

  /// Numbers the components 0, 1, ... in order of their root label (raster order of their first
  /// pixel) and folds every label's sums into its component's. Afterwards component(label) is the
  /// number of label's component, and component_moments() holds the components' sums in order.
  void number_components() {
    int count = 0;
    for (int l = 0; l < static_cast<int>(parent_.size()); ++l) {
      const int p = parent_[idx(l)];
      if (p == l) {
        // Components only move down: slot `count` is free, as its label was folded already.
        if (count != l) moments_[idx(count)] = moments_[idx(l)];
        parent_[idx(l)] = count++;
      } else {
        // p < l was renumbered already, whether root or not: its entry holds its component.
        const int c = parent_[idx(p)];
        parent_[idx(l)] = c;
        moments_[idx(c)].merge(moments_[idx(l)]);
      }
    }
    moments_.resize(idx(count));
  }

  int component(int label) const { return parent_[idx(label)]; }
  std::vector<BlobMoments>& component_moments() { return moments_; }

 private:
  static std::size_t idx(int label) { return static_cast<std::size_t>(label); }

  std::vector<int> parent_;
  std::vector<BlobMoments> moments_;
};

}  // namespace neopipe::kernels::detail
