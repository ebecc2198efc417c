#include "python/src/frames.hpp"

#include <fmt/format.h>

#include <cstring>
#include <string>

namespace neopipe::python {

void register_blob_dtype() {
  PYBIND11_NUMPY_DTYPE(BlobRow, frame, blob, area, cx, cy, x0, y0, w, h, wcx, wcy);
}

py::dtype world_blob_dtype() {
  // The BlobRow fields and X, Y side by side (not nested), so table["X"] and table["cx"] both work.
  py::list fields;
  const py::dtype row = py::dtype::of<BlobRow>();
  for (const auto& name : row.attr("names").cast<py::tuple>()) {
    fields.append(py::make_tuple(name, row.attr("fields")[name].cast<py::tuple>()[0]));
  }
  fields.append(py::make_tuple("X", py::dtype::of<double>()));
  fields.append(py::make_tuple("Y", py::dtype::of<double>()));
  return py::dtype::from_args(fields);
}

namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

cv::Mat frame_view(const py::array& a, std::optional<std::int64_t> index) {
  // Formatted only on an error: this runs once per frame of a stream.
  const auto what = [index] { return index ? fmt::format("frame {}", *index) : std::string("frame"); };
  if (a.dtype().kind() != 'u' || a.itemsize() != 1) {
    throw py::value_error(fmt::format("{}: dtype {}; neopipe takes uint8 frames (H x W gray or H x W x 3 BGR)", what(),
                                      std::string(py::str(a.dtype()))));
  }
  const bool gray = a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 1);
  if (!gray && !(a.ndim() == 3 && a.shape(2) == 3)) {
    throw py::value_error(
        fmt::format("{}: shape {}; neopipe takes H x W (gray) or H x W x 3 (BGR) frames", what(), shape_text(a)));
  }
  if (a.size() == 0) throw py::value_error(fmt::format("{}: shape {} is empty", what(), shape_text(a)));
  const int channels = gray ? 1 : 3;
  const py::ssize_t rows = a.shape(0);
  const py::ssize_t cols = a.shape(1);
  // A cv::Mat can only describe rows of contiguous pixels one positive step apart; anything else
  // (a transposed or reversed view, every other column) would need a copy, which the caller should
  // make knowingly.
  const bool pixels_contiguous =
      (a.ndim() == 2 || a.strides(2) == 1 || a.shape(2) == 1) && (cols == 1 || a.strides(1) == channels);
  const bool rows_forward = rows == 1 || a.strides(0) >= cols * channels;
  if (!pixels_contiguous || !rows_forward) {
    std::string strides;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) strides += (i > 0 ? ", " : "") + std::to_string(a.strides(i));
    throw py::value_error(fmt::format(
        "{}: strides ({}) for shape {}: neopipe reads frames in place and needs each row's pixels contiguous "
        "and rows in order (pass numpy.ascontiguousarray(frame))",
        what(), strides, shape_text(a)));
  }
  if (rows > INT32_MAX || cols > INT32_MAX) throw py::value_error(fmt::format("{}: too large", what()));
  const auto step = static_cast<std::size_t>(rows == 1 ? cols * channels : a.strides(0));
  // cv::Mat takes a non-const pointer; neopipe never writes into its source frame.
  return cv::Mat(static_cast<int>(rows), static_cast<int>(cols), CV_8UC(channels), const_cast<void*>(a.data()), step);
}

py::array blob_table(std::int64_t frame, const pipeline::BlobList& blobs) {
  py::array_t<BlobRow> out(static_cast<py::ssize_t>(blobs.size()));
  auto* row = out.mutable_data();
  for (std::size_t i = 0; i < blobs.size(); ++i, ++row) {
    const kernels::Blob& b = blobs[i];
    *row =
        BlobRow{frame, static_cast<std::int64_t>(i), b.area, b.cx, b.cy, b.x0, b.y0, b.width, b.height, b.wcx, b.wcy};
  }
  return out;
}

py::array blob_table(std::int64_t frame, const pipeline::BlobList& blobs, const std::vector<cv::Point2d>& world,
                     const py::dtype& dtype) {
  static_assert(sizeof(BlobRowWorld) == sizeof(BlobRow) + 2 * sizeof(double), "packed as the dtype");
  py::array out(dtype, std::vector<py::ssize_t>{static_cast<py::ssize_t>(blobs.size())});
  auto* row = static_cast<BlobRowWorld*>(out.mutable_data());
  for (std::size_t i = 0; i < blobs.size(); ++i, ++row) {
    const kernels::Blob& b = blobs[i];
    *row = BlobRowWorld{
        {frame, static_cast<std::int64_t>(i), b.area, b.cx, b.cy, b.x0, b.y0, b.width, b.height, b.wcx, b.wcy},
        world[i].x,
        world[i].y};
  }
  return out;
}

py::array image_array(const cv::Mat& m) {
  std::vector<py::ssize_t> shape{m.rows, m.cols};
  if (m.channels() > 1) shape.push_back(m.channels());
  py::array out = m.depth() == CV_16S ? py::array(py::dtype::of<std::int16_t>(), shape)
                                      : py::array(py::dtype::of<std::uint8_t>(), shape);
  const std::size_t row_bytes = m.cols * m.elemSize();
  auto* dst = static_cast<char*>(out.mutable_data());
  for (int y = 0; y < m.rows; ++y) std::memcpy(dst + y * row_bytes, m.ptr(y), row_bytes);
  return out;
}

}  // namespace neopipe::python
