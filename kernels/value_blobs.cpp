#include "kernels/value_blobs.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "kernels/label_forest.hpp"
#include "kernels/rows.hpp"

namespace neopipe::kernels {
namespace {

struct ValueRun {
  int xs;  ///< first pixel
  int xe;  ///< one past the last
  std::int16_t value;
  int label;
};

// Runs of equal non-zero value in one row, left to right. A ring image is mostly background, so
// zeros are skipped four pixels at a time.
int find_value_runs(const std::int16_t* row, int width, ValueRun* out) {
  int n = 0;
  int x = 0;
  while (x < width) {
    while (x + 4 <= width) {
      std::uint64_t four = 0;
      std::memcpy(&four, row + x, sizeof four);
      if (four != 0) break;
      x += 4;
    }
    while (x < width && row[x] == 0) ++x;
    if (x >= width) break;
    const std::int16_t v = row[x];
    const int xs = x;
    while (x < width && row[x] == v) ++x;
    out[n++] = {xs, x, v, 0};
  }
  return n;
}

}  // namespace

std::vector<Blob> extract_value_blobs(const cv::Mat& src, Connectivity connectivity, cv::Mat* labels) {
  detail::require_type(src, CV_16SC1, "value blobs input");
  detail::require(connectivity == Connectivity::four || connectivity == Connectivity::eight,
                  "value blobs: connectivity must be 4 or 8");
  const int width = src.cols;
  // A run above touches [xs, xe) when it overlaps it; with 8-connectivity also diagonally. Only
  // runs of the same value join.
  const int reach = connectivity == Connectivity::eight ? 1 : 0;
  // Every pixel may start a run (neighbours of different non-zero values).
  std::vector<ValueRun> buffers(2 * static_cast<std::size_t>(std::max(width, 1)));
  ValueRun* above = buffers.data();
  ValueRun* current = above + width;
  int n_above = 0;
  detail::LabelForest forest;
  std::vector<std::int16_t> label_value;  // the value of each provisional label
  struct StoredRun {
    int y;
    ValueRun run;
  };
  std::vector<StoredRun> all_runs;
  for (int y = 0; y < src.rows; ++y) {
    const int n = find_value_runs(src.ptr<std::int16_t>(y), width, current);
    int j = 0;
    for (int i = 0; i < n; ++i) {
      ValueRun& run = current[i];
      while (j < n_above && above[j].xe + reach <= run.xs) ++j;
      int label = -1;
      for (int k = j; k < n_above && above[k].xs < run.xe + reach; ++k) {
        if (above[k].value != run.value) continue;
        if (label < 0) {
          label = above[k].label;
          continue;
        }
        const int a = forest.find(label);
        const int b = forest.find(above[k].label);
        label = a == b ? a : forest.unite(a, b);
      }
      if (label < 0) {
        label = forest.create();
        label_value.push_back(run.value);
      }
      run.label = label;
      forest.moments(label).add_run(y, run.xs, run.xe, 0, 0);
      if (labels != nullptr) all_runs.push_back({y, run});
    }
    std::swap(above, current);
    n_above = n;
  }
  forest.number_components();
  const auto& components = forest.component_moments();
  std::vector<Blob> blobs;
  blobs.reserve(components.size());
  for (const auto& m : components) blobs.push_back(to_blob(m));
  // Every label of a component has the component's value: unions join runs of one value only.
  for (std::size_t l = 0; l < label_value.size(); ++l) {
    blobs[static_cast<std::size_t>(forest.component(static_cast<int>(l)))].value = label_value[l];
  }
  if (labels != nullptr) {
    labels->create(src.size(), CV_32SC1);
    labels->setTo(0);
    for (const auto& [y, run] : all_runs) {
      std::fill(labels->ptr<int>(y) + run.xs, labels->ptr<int>(y) + run.xe, forest.component(run.label) + 1);
    }
  }
  return blobs;
}

}  // namespace neopipe::kernels
