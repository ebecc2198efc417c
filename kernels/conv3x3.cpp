#include "kernels/conv3x3.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

#include "kernels/rows.hpp"

namespace neopipe::kernels {
namespace {

template <class Out>
Out saturate(int v) {
  return static_cast<Out>(std::clamp(v, int{std::numeric_limits<Out>::min()}, int{std::numeric_limits<Out>::max()}));
}

template <class Out>
void row_impl(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, Out* out, int width,
              const Conv3x3& k) {
  const auto& w = k.weights;
  const int shift = k.shift;
  const int bias = shift > 0 ? 1 << (shift - 1) : 0;
  // An arithmetic right shift floors, so adding half first rounds halves toward +infinity.
  const auto finish = [&](int acc) { return saturate<Out>((acc + bias) >> shift); };
  detail::border_pixels(detail::RowTriple<std::uint8_t>{up, mid, down}, width, k.border,
                        [&](int x, const std::array<int, 9>& p) {
                          int acc = 0;
                          for (size_t i = 0; i < 9; ++i) acc += w[i] * p[i];
                          out[x] = finish(acc);
                        });
  for (int x = 1; x < width - 1; ++x) {
    const int acc = w[0] * up[x - 1] + w[1] * up[x] + w[2] * up[x + 1] + w[3] * mid[x - 1] + w[4] * mid[x] +
                    w[5] * mid[x + 1] + w[6] * down[x - 1] + w[7] * down[x] + w[8] * down[x + 1];
    out[x] = finish(acc);
  }
}

template <class Out>
void frame_impl(const cv::Mat& src, cv::Mat& dst, const Conv3x3& k, cv::Range r) {
  const detail::NeighbourRows<std::uint8_t> rows(src, k.border);
  for (int y = r.start; y < r.end; ++y) {
    const auto t = rows.at(y);
    conv3x3_row(t.up, t.mid, t.down, dst.ptr<Out>(y), src.cols, k);
  }
}

}  // namespace

void validate(const Conv3x3& k) {
  for (int w : k.weights) {
    detail::require(std::abs(w) <= 65535, "conv3x3: weights must lie in -65535..65535");
  }
  detail::require(k.shift >= 0 && k.shift <= 16, "conv3x3: shift must lie in 0..16");
  detail::require(k.border.mode != BorderMode::constant || (k.border.value >= 0 && k.border.value <= 255),
                  "conv3x3: the constant border value must lie in 0..255");
}

void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::uint8_t* out,
                 int width, const Conv3x3& k) noexcept {
  row_impl(up, mid, down, out, width, k);
}

void conv3x3_row(const std::uint8_t* up, const std::uint8_t* mid, const std::uint8_t* down, std::int16_t* out,
                 int width, const Conv3x3& k) noexcept {
  row_impl(up, mid, down, out, width, k);
}

void conv3x3(const cv::Mat& src, cv::Mat& dst, const Conv3x3& k, int dst_type, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "conv3x3 input");
  detail::require_distinct(src, dst, "conv3x3");
  validate(k);
  if (rows != cv::Range::all() && !dst.empty()) dst_type = dst.type();
  detail::require(dst_type == CV_8UC1 || dst_type == CV_16SC1, "conv3x3: output must be CV_8UC1 or CV_16SC1");
  const cv::Range r = detail::output_rows(dst, src.size(), dst_type, rows);
  if (dst_type == CV_8UC1) {
    frame_impl<std::uint8_t>(src, dst, k, r);
  } else {
    frame_impl<std::int16_t>(src, dst, k, r);
  }
}

Conv3x3 smooth3x3() {
  return {{1, 2, 1, 2, 4, 2, 1, 2, 1}, 4, {}};
}
Conv3x3 sobel_x3x3() {
  return {{-1, 0, 1, -2, 0, 2, -1, 0, 1}, 0, {}};
}
Conv3x3 sobel_y3x3() {
  return {{-1, -2, -1, 0, 0, 0, 1, 2, 1}, 0, {}};
}

}  // namespace neopipe::kernels
