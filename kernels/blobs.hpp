#pragma once
// Blob extraction, PIPE's iconic-to-symbolic step: connected components of (value > T) with their
// area, bounding box, centroid, intensity-weighted centroid and second central moments.
//
// The components are labelled from runs (maximal horizontal spans of foreground in a row) joined by
// union-find, and the moments are accumulated as integer sums while scanning, so no label image is
// written unless one is asked for. Integer sums are exact, so merging partial results (stripes) in
// any order gives identical blobs.

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
};

Blob to_blob(const BlobMoments& m) noexcept;

/// Components of (src > threshold), ordered by their first pixel in raster order.
/// src is CV_8UC1; `weights` (CV_8UC1, same size) defaults to src. If `labels` is given it receives
/// a CV_32SC1 label image: 0 for background, i + 1 for the pixels of blob i.
std::vector<Blob> extract_blobs(const cv::Mat& src, const BlobParams& params, const cv::Mat& weights = cv::Mat(),
                                cv::Mat* labels = nullptr);

}  // namespace neopipe::kernels
