#pragma once
// Row iteration shared by the kernels: argument checks and the three-row window that 3x3 kernels
// slide down the image, with the vertical border applied. The horizontal border is applied by each
// row function at its first and last pixel, so the interior loop stays branch-free.

#include <algorithm>
#include <array>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/types.hpp"

namespace neopipe::kernels::detail {

void require(bool ok, const char* what);
void require_type(const cv::Mat& m, int type, const char* what);
void require_same_size(const cv::Mat& a, const cv::Mat& b, const char* what);
/// Neighbourhood kernels read rows they have already written if the output shares memory with
/// the input, so that is refused.
void require_distinct(const cv::Mat& src, const cv::Mat& dst, const char* what);
/// The rows to compute, clamped to the image. With `rows == cv::Range::all()` the output is
/// (re)allocated as needed, so whole-frame calls are convenient; with a row range (a stripe), the
/// output must already have `size` and `type`, because other stripes share it.
cv::Range output_rows(cv::Mat& dst, cv::Size size, int type, cv::Range rows);

/// The three input rows around output row y.
template <class T>
struct RowTriple {
  const T* up;
  const T* mid;
  const T* down;
};

/// Supplies rows y-1, y, y+1 of `src` with the border applied at the top and bottom edges.
template <class T>
class NeighbourRows {
 public:
  NeighbourRows(const cv::Mat& src, const Border& border) : src_(src), border_(border) {
    if (border.mode == BorderMode::constant) {
      constant_row_.assign(static_cast<size_t>(src.cols), static_cast<T>(border.value));
    }
  }

  RowTriple<T> at(int y) const { return {row(y - 1), src_.ptr<T>(y), row(y + 1)}; }

 private:
  const T* row(int y) const {
    if (y >= 0 && y < src_.rows) return src_.ptr<T>(y);
    if (border_.mode == BorderMode::constant) return constant_row_.data();
    return src_.ptr<T>(std::clamp(y, 0, src_.rows - 1));
  }

  const cv::Mat& src_;
  Border border_;
  std::vector<T> constant_row_;
};

/// The 3x3 neighbourhood of pixel x in reading order (NW, N, NE, W, C, E, SW, S, SE), with the
/// horizontal border applied. Used for the first and last pixel of a row.
template <class T>
std::array<int, 9> gather3x3(const RowTriple<T>& r, int x, int width, const Border& border) {
  std::array<int, 9> p{};
  const std::array<const T*, 3> rows{r.up, r.mid, r.down};
  for (int dy = 0; dy < 3; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = x + dx;
      int v = 0;
      if (xx >= 0 && xx < width) {
        v = rows[dy][xx];
      } else if (border.mode == BorderMode::constant) {
        v = border.value;
      } else {
        v = rows[dy][std::clamp(xx, 0, width - 1)];
      }
      p[static_cast<size_t>(dy) * 3 + static_cast<size_t>(dx + 1)] = v;
    }
  }
  return p;
}

/// Applies `pixel(std::array<int,9>)` at the row's first and last pixel (the only ones that touch
/// the horizontal border); the caller's interior loop covers 1..width-2.
template <class T, class Pixel>
void border_pixels(const RowTriple<T>& r, int width, const Border& border, Pixel&& pixel) {
  pixel(0, gather3x3(r, 0, width, border));
  if (width > 1) pixel(width - 1, gather3x3(r, width - 1, width, border));
}

}  // namespace neopipe::kernels::detail
