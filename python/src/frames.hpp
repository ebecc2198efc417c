#pragma once
// numpy <-> neopipe: frames in as cv::Mat views of the caller's memory (no copy), blob tables out as
// numpy structured arrays with the columns of the CLI's blob table.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

#include "pipeline/value.hpp"

namespace neopipe::python {

namespace py = pybind11;

/// One row of the blob table, in the column order `neopipe run` writes (pipeline/io/blob_table_writer.hpp).
struct BlobRow {
  std::int64_t frame;
  std::int64_t blob;
  std::int64_t area;
  double cx;
  double cy;
  std::int32_t x0;
  std::int32_t y0;
  std::int32_t w;
  std::int32_t h;
  double wcx;
  double wcy;
};

/// A row with the calibration's columns: `neopipe run --calib`'s X,Y (workspace mm of wcx, wcy).
struct BlobRowWorld {
  BlobRow blob;
  double X;  // NOLINT(readability-identifier-naming): the CLI's column names
  double Y;
};

/// Registers BlobRow's and BlobRowWorld's numpy dtypes; call once from the module's init.
void register_blob_dtype();

/// `array` as a cv::Mat over the same memory: uint8, H x W (gray) or H x W x 3 (BGR, as cv2 gives
/// it; H x W x 1 is gray too), pixels contiguous within a row, rows in order (row padding is fine).
/// Throws py::value_error naming the frame and the cause otherwise. The Mat does not own the memory:
/// the caller keeps `array` alive while the Mat is in use.
/// `index`, when given, names the frame in messages ("frame 3: ..."), else "frame: ...".
cv::Mat frame_view(const py::array& array, std::optional<std::int64_t> index = std::nullopt);

/// One frame's blobs as a structured array of BlobRow, `frame` in every row.
py::array blob_table(std::int64_t frame, const pipeline::BlobList& blobs);
/// The same with X,Y columns, `world[i]` for blob i; `dtype` is world_blob_dtype() (made once by the caller).
py::array blob_table(std::int64_t frame, const pipeline::BlobList& blobs, const std::vector<cv::Point2d>& world,
                     const py::dtype& dtype);
/// The dtype of blob_table's rows with X,Y, flat (frame, ..., wcy, X, Y), as the CLI's columns.
py::dtype world_blob_dtype();

/// An image port's value (cv::Mat) as a new numpy array (a copy: the engine reuses its buffers).
py::array image_array(const cv::Mat& image);

}  // namespace neopipe::python
