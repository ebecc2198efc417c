#include "kernels/rows.hpp"

#include <string>

namespace neopipe::kernels::detail {

void require(bool ok, const char* what) {
  if (!ok) throw KernelError(what);
}

void require_type(const cv::Mat& m, int type, const char* what) {
  if (m.empty() || m.type() != type || m.dims != 2) {
    throw KernelError(std::string(what) + ": expected a non-empty 2-D image of type " + cv::typeToString(type) +
                      (m.empty() ? std::string(", got an empty one") : ", got " + cv::typeToString(m.type())));
  }
}

void require_same_size(const cv::Mat& a, const cv::Mat& b, const char* what) {
  if (a.size() != b.size()) throw KernelError(std::string(what) + ": images differ in size");
}

void require_distinct(const cv::Mat& src, const cv::Mat& dst, const char* what) {
  if (src.empty() || dst.empty()) return;
  const bool overlap = src.datastart < dst.dataend && dst.datastart < src.dataend;
  if (overlap) throw KernelError(std::string(what) + ": the output must not share memory with the input");
}

cv::Range output_rows(cv::Mat& dst, cv::Size size, int type, cv::Range rows) {
  if (rows == cv::Range::all()) {
    dst.create(size, type);
    return {0, size.height};
  }
  if (dst.size() != size || dst.type() != type) {
    throw KernelError("output image must be allocated with the input's size and type " + cv::typeToString(type));
  }
  return {std::max(rows.start, 0), std::min(rows.end, size.height)};
}

}  // namespace neopipe::kernels::detail
