#pragma once
// Blob extraction on a label image (the blob kernel's s16 mode): connected components of pixels of
// equal non-zero value, so two touching regions of different values stay two blobs, and 0 is
// background. Made for the panoramic sensor's ring image, where a marble's disc has the value
// id + 1 and a nearer disc may cover part of a farther one (qualnav.md §2).
//
// The same run-based labelling as extract_blobs (kernels/blobs.hpp): runs are maximal horizontal
// spans of one value, joined by union-find to touching runs of the same value in the row above, and
// the moments are exact integer sums. Each blob carries the table's columns (area, box, centroid,
// central moments) and its value; there are no weights, so the weighted centroid equals the centroid.
// Columns do not wrap: a region cut by the image's left and right edges is two blobs of one value,
// for the reader to join.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/blobs.hpp"
#include "kernels/types.hpp"

namespace neopipe::kernels {

inline constexpr Footprint value_blobs_footprint = Footprint::frame;

/// Components of equal non-zero value of `src` (CV_16SC1; negative values are values like any
/// other), ordered by their first pixel in raster order, each with Blob::value set. If `labels` is
/// given it receives a CV_32SC1 label image: 0 for background, i + 1 for the pixels of blob i.
/// Throws KernelError for another type or a bad connectivity.
std::vector<Blob> extract_value_blobs(const cv::Mat& src, Connectivity connectivity, cv::Mat* labels = nullptr);

}  // namespace neopipe::kernels
