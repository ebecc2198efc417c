#include "kernels/blobs.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "kernels/blob_runs.hpp"
#include "kernels/label_forest.hpp"
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

using detail::LabelForest;
using detail::Run;

// Labels rows [rows.start, rows.end) of src into `forest`, calling on_row(y, runs, n) with each
// row's runs once they carry their labels.
template <class OnRow>
void label_rows(const cv::Mat& src, const cv::Mat& weights, const BlobParams& params, cv::Range rows,
                LabelForest& forest, OnRow&& on_row) {
  const int width = src.cols;
  // A run above touches [xs, xe) when it overlaps it; with 8-connectivity also diagonally.
  const int reach = params.connectivity == Connectivity::eight ? 1 : 0;
  std::vector<Run> buffers(2 * static_cast<std::size_t>(detail::max_runs(width)));
  Run* above = buffers.data();
  Run* current = above + detail::max_runs(width);
  int n_above = 0;
  for (int y = rows.start; y < rows.end; ++y) {
    int n = 0;
    if (params.threshold < 0) {
      current[0] = {0, width, 0};
      n = 1;
    } else {
      n = detail::find_runs(src.ptr<std::uint8_t>(y), width, static_cast<std::uint8_t>(params.threshold), current);
    }
    const auto* wrow = weights.ptr<std::uint8_t>(y);
    int j = 0;
    for (int i = 0; i < n; ++i) {
      Run& run = current[i];
      while (j < n_above && above[j].xe + reach <= run.xs) ++j;
      int k = j;
      int label = 0;
      if (k < n_above && above[k].xs < run.xe + reach) {
        label = above[k].label;
        for (++k; k < n_above && above[k].xs < run.xe + reach; ++k) {
          const int a = forest.find(label);
          const int b = forest.find(above[k].label);
          label = a == b ? a : forest.unite(a, b);
        }
      } else {
        label = forest.create();
      }
      run.label = label;
      const auto [sw, swx] = detail::weight_sums(wrow, width, run.xs, run.xe);
      forest.moments(label).add_run(y, run.xs, run.xe, sw, swx);
    }
    on_row(y, static_cast<const Run*>(current), n);
    std::swap(above, current);
    n_above = n;
  }
}

// Checks extract_blobs' and label_stripe's arguments; returns the weight image to use.
const cv::Mat& checked_weights(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights) {
  detail::require_type(src, CV_8UC1, "blobs input");
  detail::require(params.threshold >= -1 && params.threshold <= 255, "blobs: threshold must lie in -1..255");
  detail::require(params.connectivity == Connectivity::four || params.connectivity == Connectivity::eight,
                  "blobs: connectivity must be 4 or 8");
  const cv::Mat& w = weights.empty() ? src : weights;
  detail::require_type(w, CV_8UC1, "blobs weights");
  detail::require_same_size(src, w, "blobs input and weights");
  return w;
}

std::vector<Blob> to_blobs(const std::vector<BlobMoments>& components) {
  std::vector<Blob> blobs;
  blobs.reserve(components.size());
  for (const auto& m : components) blobs.push_back(to_blob(m));
  return blobs;
}

}  // namespace

void BlobMoments::add_run(int y, int xs, int xe, const std::uint8_t* weights) noexcept {
  const auto [run_sw, run_swx] = detail::weight_sums(weights, xs, xe);
  add_run(y, xs, xe, run_sw, run_swx);
}

void BlobMoments::add_run(int y, int xs, int xe, std::int64_t run_sw, std::int64_t run_swx) noexcept {
  const std::int64_t n = xe - xs;
  const std::int64_t run_sx = sum_to(xe) - sum_to(xs);
  const std::int64_t yy = y;
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
  const cv::Mat& w = checked_weights(src, params, weights);
  struct StoredRun {
    int y;
    Run run;
  };
  LabelForest forest;
  std::vector<StoredRun> all_runs;
  label_rows(src, w, params, {0, src.rows}, forest, [&](int y, const Run* runs, int n) {
    if (labels != nullptr) {
      for (int i = 0; i < n; ++i) all_runs.push_back({y, runs[i]});
    }
  });
  forest.number_components();
  if (labels != nullptr) {
    labels->create(src.size(), CV_32SC1);
    labels->setTo(0);
    for (const auto& [y, run] : all_runs) {
      std::fill(labels->ptr<int>(y) + run.xs, labels->ptr<int>(y) + run.xe, forest.component(run.label) + 1);
    }
  }
  return to_blobs(forest.component_moments());
}

BlobStripe label_stripe(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights, cv::Range rows) {
  const cv::Mat& w = checked_weights(src, params, weights);
  if (rows == cv::Range::all()) rows = {0, src.rows};
  rows.start = std::clamp(rows.start, 0, src.rows);
  rows.end = std::clamp(rows.end, rows.start, src.rows);
  BlobStripe stripe;
  stripe.frame_ = src.size();
  stripe.params_ = params;
  stripe.rows_ = rows;
  if (rows.empty()) return stripe;
  LabelForest forest;
  // Provisional labels for now; turned into piece numbers once the forest is folded.
  const auto keep = [](std::vector<BlobStripe::EdgeRun>& edge, const Run* runs, int n) {
    edge.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) edge.push_back({runs[i].xs, runs[i].xe, runs[i].label});
  };
  label_rows(src, w, params, rows, forest, [&](int y, const Run* runs, int n) {
    if (y == rows.start) keep(stripe.top_, runs, n);
    if (y == rows.end - 1) keep(stripe.bottom_, runs, n);
  });
  forest.number_components();
  for (auto* edge : {&stripe.top_, &stripe.bottom_}) {
    for (auto& run : *edge) run.piece = forest.component(run.piece);
  }
  stripe.pieces_ = std::move(forest.component_moments());
  return stripe;
}

std::vector<Blob> merge_stripes(std::vector<BlobStripe> stripes, const BlobParams& params) {
  detail::require(!stripes.empty(), "merge_stripes: no stripes");
  const cv::Size frame = stripes.front().frame_;
  detail::require(frame.width > 0 && frame.height > 0, "merge_stripes: a stripe was not made by label_stripe");
  int next_row = 0;
  std::size_t total = 0;
  for (const auto& s : stripes) {
    detail::require(s.frame_ == frame, "merge_stripes: stripes of frames of different sizes");
    detail::require(s.params_.threshold == params.threshold && s.params_.connectivity == params.connectivity,
                    "merge_stripes: a stripe was labelled with other parameters");
    if (s.rows_.empty()) continue;
    detail::require(s.rows_.start == next_row,
                    "merge_stripes: stripes must cover the frame's rows top to bottom without gaps or overlaps");
    next_row = s.rows_.end;
    total += s.pieces_.size();
  }
  detail::require(next_row == frame.height,
                  "merge_stripes: stripes must cover the frame's rows top to bottom without gaps or overlaps");

  // Pieces numbered stripe after stripe, each stripe's in raster order, are numbered in raster order
  // of their first pixel over the whole frame, which is what LabelForest needs.
  std::vector<BlobMoments> pieces;
  pieces.reserve(total);
  for (const auto& s : stripes) pieces.insert(pieces.end(), s.pieces_.begin(), s.pieces_.end());
  LabelForest forest(std::move(pieces));
  const int reach = params.connectivity == Connectivity::eight ? 1 : 0;
  const BlobStripe* upper = nullptr;
  int upper_base = 0;
  int base = 0;
  for (const auto& s : stripes) {
    if (s.rows_.empty()) continue;
    if (upper != nullptr) {
      // The same touching rule as between the rows of one stripe.
      const auto& above = upper->bottom_;
      std::size_t j = 0;
      for (const auto& run : s.top_) {
        while (j < above.size() && above[j].xe + reach <= run.xs) ++j;
        for (std::size_t k = j; k < above.size() && above[k].xs < run.xe + reach; ++k) {
          const int a = forest.find(upper_base + above[k].piece);
          const int b = forest.find(base + run.piece);
          if (a != b) forest.unite(a, b);
        }
      }
    }
    upper = &s;
    upper_base = base;
    base += static_cast<int>(s.pieces_.size());
  }
  forest.number_components();
  return to_blobs(forest.component_moments());
}

}  // namespace neopipe::kernels
