#pragma once
// What flows along the graph's edges: typed port values.

#include <opencv2/core/mat.hpp>
#include <optional>
#include <string_view>
#include <variant>
#include <vector>

#include "kernels/blobs.hpp"
#include "kernels/histogram.hpp"

namespace neopipe::pipeline {

/// The type of a port. Images all have the frame's size; their pixel format is part of the type.
enum class PortType {
  bgr8,       ///< 8-bit, three channels in OpenCV's B, G, R order (CV_8UC3)
  gray8,      ///< 8-bit, one channel (CV_8UC1)
  s16,        ///< 16-bit signed, one channel (CV_16SC1)
  histogram,  ///< 256 bin counts
  blobs,      ///< a blob table, ordered by first pixel in raster order
};

std::string_view to_string(PortType t);
std::optional<PortType> port_type_from_string(std::string_view name);
bool is_image(PortType t);
/// The OpenCV type of an image port (CV_8UC3, CV_8UC1 or CV_16SC1); -1 for symbolic ports.
int cv_type(PortType t);

using Histogram = kernels::Histogram;
using BlobList = std::vector<kernels::Blob>;

/// One port's value for one frame. monostate means "not produced".
using Value = std::variant<std::monostate, cv::Mat, Histogram, BlobList>;

/// A value of type t for frame size `size` with every pixel (or count) set to `fill`; an empty blob
/// table for blobs. Used for delay edges' initial values.
Value constant_value(PortType t, cv::Size size, int fill);

}  // namespace neopipe::pipeline
