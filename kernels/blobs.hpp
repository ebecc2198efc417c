#pragma once
// Blob extraction, PIPE's iconic-to-symbolic step: connected components of (value > T) with their
// area, bounding box, centroid, intensity-weighted centroid and second central moments.
//
// The components are labelled from runs (maximal horizontal spans of foreground in a row) joined by
// union-find, and the moments are accumulated as integer sums while scanning, so no label image is
// written unless one is asked for. Integer sums are exact, so merging partial results (stripes) in
// any order gives identical blobs.
//
// Stripes: kernels have no threads, so a caller that wants a frame's blobs from several threads
// labels horizontal stripes of it with label_stripe, one call per thread, and joins them with
// merge_stripes:
//
//   std::vector<BlobStripe> stripes(n);
//   parallel_for(i in 0..n) stripes[i] = label_stripe(src, params, weights, {cuts[i], cuts[i + 1]});
//   std::vector<Blob> blobs = merge_stripes(std::move(stripes), params);  // == extract_blobs(src, ...)

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint blobs_footprint = Footprint::frame;

enum class Connectivity { four = 4, eight = 8 };

struct BlobParams {
  /// Foreground is value > threshold; -1 makes every pixel foreground.
  int threshold = 0;
  Connectivity connectivity = Connectivity::eight;
};

/// Exact sums over a component's pixels (x, y are column and row indices; g the weight).
struct BlobMoments {
  std::int64_t area = 0;
  std::int64_t sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  std::int64_t sw = 0, swx = 0, swy = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  ///< inclusive bounding box

  /// Adds the run [xs, xe) of row y; `weights` points at row y of the weight image.
  void add_run(int y, int xs, int xe, const std::uint8_t* weights) noexcept;
  /// The same with the run's weight sums already taken: sw = sum w, swx = sum w * x.
  void add_run(int y, int xs, int xe, std::int64_t run_sw, std::int64_t run_swx) noexcept;
  void merge(const BlobMoments& other) noexcept;
};

struct Blob {
  std::int64_t area = 0;
  int x0 = 0, y0 = 0, width = 0, height = 0;  ///< bounding box
  double cx = 0, cy = 0;                      ///< mean pixel position (OpenCV's centroid)
  /// Intensity-weighted centroid, weights = gray values; equal to (cx, cy) if all weights are 0.
  double wcx = 0, wcy = 0;
  /// Second central moments as cv::moments of the component's mask: sum (x - cx)^2,
  /// sum (x - cx)(y - cy), sum (y - cy)^2.
  double mu20 = 0, mu11 = 0, mu02 = 0;
  /// The pixel value every pixel of the component shares, for components of equal values
  /// (kernels/value_blobs.hpp); 0 for components of a threshold.
  int value = 0;
};

Blob to_blob(const BlobMoments& m) noexcept;

/// Components of (src > threshold), ordered by their first pixel in raster order.
/// src is CV_8UC1; `weights` (CV_8UC1, same size) defaults to src. If `labels` is given it receives
/// a CV_32SC1 label image: 0 for background, i + 1 for the pixels of blob i.
std::vector<Blob> extract_blobs(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights = cv::Mat(),
                                cv::Mat* labels = nullptr);

/// The blobs of one horizontal stripe of a frame, with what is needed to join them to the blobs of
/// the neighbouring stripes: the stripe's components ("pieces" of the frame's blobs) as exact sums,
/// in raster order of their first pixel, and the runs of the stripe's first and last rows, each
/// tagged with its piece. Made by label_stripe, consumed by merge_stripes; movable and copyable.
class BlobStripe {
 public:
  /// An empty stripe of no frame; merge_stripes refuses it.
  BlobStripe() = default;

  /// The frame rows this stripe covers (after clamping to the frame; may be empty).
  cv::Range rows() const noexcept { return rows_; }
  /// Components within the stripe, before joining: a blob that crosses stripe borders has a piece
  /// in each stripe it touches (several if it is not connected inside a stripe, like a U's arms).
  std::size_t pieces() const noexcept { return pieces_.size(); }

 private:
  friend BlobStripe label_stripe(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights, cv::Range rows);
  friend std::vector<Blob> merge_stripes(std::vector<BlobStripe> stripes, const BlobParams& params);

  struct EdgeRun {
    int xs;     ///< first pixel
    int xe;     ///< one past the last pixel
    int piece;  ///< index into pieces_
  };

  cv::Size frame_{};
  BlobParams params_{};
  cv::Range rows_{0, 0};
  std::vector<BlobMoments> pieces_;
  std::vector<EdgeRun> top_;     ///< runs of the first row
  std::vector<EdgeRun> bottom_;  ///< runs of the last row (the same as top_ for a one-row stripe)
};

/// Labels rows `rows` of src: foreground is value > params.threshold, weights as in extract_blobs
/// (an empty `weights` means src). `rows` is clamped to the frame, and cv::Range::all() is the
/// whole frame. Reads only those rows of src and weights, so stripes may be labelled concurrently.
BlobStripe label_stripe(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights, cv::Range rows);

/// Joins stripes that cover the frame's rows, given top to bottom (empty stripes are ignored), into
/// exactly the blobs extract_blobs returns for the whole frame: the same order (first pixel in
/// raster order) and bit-identical values. Pieces of adjacent stripes are joined where a run on the
/// last row of one touches a run on the first row of the next (overlap for 4-connectivity, overlap
/// or a diagonal touch for 8). Throws KernelError if the stripes are of different frames or
/// parameters (params must be the ones they were labelled with), or leave a gap or overlap.
std::vector<Blob> merge_stripes(std::vector<BlobStripe> stripes, const BlobParams& params);

}  // namespace neopipe::kernels
