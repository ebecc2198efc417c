#include "kernels/blobs.hpp"

#include <algorithm>
#include <numeric>

#include "kernels/rows.hpp"

namespace neopipe::kernels {
namespace {

// A 128-bit integer for exact central moments (a GCC/Clang extension, hence __extension__).
__extension__ using int128 = __int128;

// Sum of x and of x^2 for x = 0..n-1.
constexpr std::int64_t sum_to(std::int64_t n) {
  return n * (n - 1) / 2;
}
constexpr std::int64_t sum_sq_to(std::int64_t n) {
  return (n - 1) * n * (2 * n - 1) / 6;
}

struct Run {
  int xs;     // first pixel
  int xe;     // one past the last pixel
  int label;  // provisional label (a union-find node)
};

struct StoredRun {
  int y;
  Run run;
};

// Provisional labels are created in raster order of the run that starts them, and a component's
// first run always starts a new label (nothing above it can belong to it). Keeping the smaller label
// as the root on every union therefore makes each root the component's raster-first label.
class Components {
 public:
  int create() {
    const int label = static_cast<int>(parent_.size());
    parent_.push_back(label);
    moments_.emplace_back();
    return label;
  }

  int find(int label) {
    int root = label;
    while (parent_[static_cast<size_t>(root)] != root) root = parent_[static_cast<size_t>(root)];
    while (parent_[static_cast<size_t>(label)] != root) {
      const int next = parent_[static_cast<size_t>(label)];
      parent_[static_cast<size_t>(label)] = root;
      label = next;
    }
    return root;
  }

  // Joins two roots; returns the surviving root.
  int unite(int a, int b) {
    if (a == b) return a;
    if (b < a) std::swap(a, b);
    parent_[static_cast<size_t>(b)] = a;
    moments_[static_cast<size_t>(a)].merge(moments_[static_cast<size_t>(b)]);
    return a;
  }

  BlobMoments& moments(int root) { return moments_[static_cast<size_t>(root)]; }
  int size() const { return static_cast<int>(parent_.size()); }

 private:
  std::vector<int> parent_;
  std::vector<BlobMoments> moments_;
};

void find_runs(const std::uint8_t* row, int width, std::uint8_t t, std::vector<Run>& runs) {
  int x = 0;
  while (x < width) {
    while (x < width && row[x] <= t) ++x;
    if (x == width) break;
    const int xs = x;
    while (x < width && row[x] > t) ++x;
    runs.push_back({xs, x, -1});
  }
}

}  // namespace

void BlobMoments::add_run(int y, int xs, int xe, const std::uint8_t* weights) noexcept {
  const std::int64_t n = xe - xs;
  const std::int64_t run_sx = sum_to(xe) - sum_to(xs);
  const std::int64_t yy = y;
  std::int64_t run_sw = 0;
  std::int64_t run_swx = 0;
  for (int x = xs; x < xe; ++x) {
    run_sw += weights[x];
    run_swx += std::int64_t{weights[x]} * x;
  }
  if (area == 0) {
    x0 = xs;
    y0 = y;
    x1 = xe - 1;
    y1 = y;
  } else {
    x0 = std::min(x0, xs);
    y0 = std::min(y0, y);
    x1 = std::max(x1, xe - 1);
    y1 = std::max(y1, y);
  }
  area += n;
  sx += run_sx;
  sy += yy * n;
  sxx += sum_sq_to(xe) - sum_sq_to(xs);
  sxy += yy * run_sx;
  syy += yy * yy * n;
  sw += run_sw;
  swx += run_swx;
  swy += yy * run_sw;
}

void BlobMoments::merge(const BlobMoments& o) noexcept {
  if (o.area == 0) return;
  if (area == 0) {
    *this = o;
    return;
  }
  area += o.area;
  sx += o.sx;
  sy += o.sy;
  sxx += o.sxx;
  sxy += o.sxy;
  syy += o.syy;
  sw += o.sw;
  swx += o.swx;
  swy += o.swy;
  x0 = std::min(x0, o.x0);
  y0 = std::min(y0, o.y0);
  x1 = std::max(x1, o.x1);
  y1 = std::max(y1, o.y1);
}

Blob to_blob(const BlobMoments& m) noexcept {
  Blob b;
  b.area = m.area;
  b.x0 = m.x0;
  b.y0 = m.y0;
  b.width = m.x1 - m.x0 + 1;
  b.height = m.y1 - m.y0 + 1;
  if (m.area == 0) return b;
  const auto area = static_cast<double>(m.area);
  b.cx = static_cast<double>(m.sx) / area;
  b.cy = static_cast<double>(m.sy) / area;
  if (m.sw > 0) {
    b.wcx = static_cast<double>(m.swx) / static_cast<double>(m.sw);
    b.wcy = static_cast<double>(m.swy) / static_cast<double>(m.sw);
  } else {
    b.wcx = b.cx;
    b.wcy = b.cy;
  }
  // sum (x - cx)^2 = (area * sxx - sx^2) / area; the numerator is exact in 128 bits, so there is
  // no cancellation however far the blob lies from the origin.
  const auto central = [&](std::int64_t sab, std::int64_t sa, std::int64_t sb) {
    const int128 num = static_cast<int128>(m.area) * sab - static_cast<int128>(sa) * sb;
    return static_cast<double>(num) / area;
  };
  b.mu20 = central(m.sxx, m.sx, m.sx);
  b.mu11 = central(m.sxy, m.sx, m.sy);
  b.mu02 = central(m.syy, m.sy, m.sy);
  return b;
}

std::vector<Blob> extract_blobs(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights, cv::Mat* labels) {
  detail::require_type(src, CV_8UC1, "blobs input");
  detail::require(params.threshold >= -1 && params.threshold <= 255, "blobs: threshold must lie in -1..255");
  const cv::Mat& w = weights.empty() ? src : weights;
  detail::require_type(w, CV_8UC1, "blobs weights");
  detail::require_same_size(src, w, "blobs input and weights");

  const bool eight = params.connectivity == Connectivity::eight;
  // A run above touches [xs, xe) when it overlaps it; with 8-connectivity also diagonally.
  const int reach = eight ? 1 : 0;
  Components comps;
  std::vector<Run> above;
  std::vector<Run> current;
  std::vector<StoredRun> all_runs;

  for (int y = 0; y < src.rows; ++y) {
    current.clear();
    if (params.threshold < 0) {
      current.push_back({0, src.cols, -1});
    } else {
      find_runs(src.ptr<std::uint8_t>(y), src.cols, static_cast<std::uint8_t>(params.threshold), current);
    }
    const std::uint8_t* wrow = w.ptr<std::uint8_t>(y);
    size_t j = 0;
    for (Run& run : current) {
      while (j < above.size() && above[j].xe + reach <= run.xs) ++j;
      int label = -1;
      for (size_t k = j; k < above.size() && above[k].xs < run.xe + reach; ++k) {
        const int root = comps.find(above[k].label);
        label = label < 0 ? root : comps.unite(label, root);
      }
      if (label < 0) label = comps.create();
      run.label = label;
      comps.moments(label).add_run(y, run.xs, run.xe, wrow);
      if (labels != nullptr) all_runs.push_back({y, run});
    }
    std::swap(above, current);
  }

  std::vector<Blob> blobs;
  std::vector<int> final_label(static_cast<size_t>(comps.size()), 0);
  for (int l = 0; l < comps.size(); ++l) {
    if (comps.find(l) != l) continue;
    blobs.push_back(to_blob(comps.moments(l)));
    final_label[static_cast<size_t>(l)] = static_cast<int>(blobs.size());
  }
  if (labels != nullptr) {
    labels->create(src.size(), CV_32SC1);
    labels->setTo(0);
    for (const auto& [y, run] : all_runs) {
      const int l = final_label[static_cast<size_t>(comps.find(run.label))];
      std::fill(labels->ptr<int>(y) + run.xs, labels->ptr<int>(y) + run.xe, l);
    }
  }
  return blobs;
}

}  // namespace neopipe::kernels
