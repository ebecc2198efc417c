#include "kernels/histogram.hpp"

#include <algorithm>

#include "kernels/rows.hpp"

namespace neopipe::kernels {

void accumulate_histogram(const cv::Mat& src, Histogram& hist, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "histogram input");
  const int y0 = rows == cv::Range::all() ? 0 : std::max(rows.start, 0);
  const int y1 = rows == cv::Range::all() ? src.rows : std::min(rows.end, src.rows);
  // Four interleaved count tables break the store-to-load dependency on runs of equal pixels.
  std::array<std::array<std::uint32_t, 256>, 4> partial{};
  // Flush to the 64-bit totals before a 32-bit count could overflow.
  const std::int64_t flush_every = std::max<std::int64_t>(1, std::int64_t{0xFFFFFFFF} / std::max(src.cols, 1));
  for (int y = y0; y < y1; ++y) {
    const auto* p = src.ptr<std::uint8_t>(y);
    int x = 0;
    for (; x + 4 <= src.cols; x += 4) {
      ++partial[0][p[x]];
      ++partial[1][p[x + 1]];
      ++partial[2][p[x + 2]];
      ++partial[3][p[x + 3]];
    }
    for (; x < src.cols; ++x) ++partial[0][p[x]];
    if ((y - y0) % flush_every == flush_every - 1 || y == y1 - 1) {
      for (const auto& part : partial) {
        for (size_t i = 0; i < 256; ++i) hist[i] += part[i];
      }
      partial = {};
    }
  }
}

Histogram histogram(const cv::Mat& src) {
  Histogram h{};
  accumulate_histogram(src, h);
  return h;
}

}  // namespace neopipe::kernels
