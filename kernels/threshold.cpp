#include "kernels/threshold.hpp"

#include <algorithm>
#include <cfloat>

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {

void threshold_row(const std::uint8_t* in, std::uint8_t* out, int width, std::uint8_t t, std::uint8_t high) noexcept {
  const auto scalar = [&](size_t x0, size_t x1) {
    for (size_t x = x0; x < x1; ++x) out[x] = in[x] > t ? high : std::uint8_t{0};
  };
#if HWY_TARGET != HWY_SCALAR
  namespace hn = simd::hn;
  const hn::ScalableTag<std::uint8_t> d;
  const auto vt = hn::Set(d, t);
  const auto vhigh = hn::Set(d, high);
  simd::point_row(
      d, out, static_cast<size_t>(width),
      [&](size_t x) { return hn::IfThenElseZero(hn::Gt(hn::LoadU(d, in + x), vt), vhigh); }, scalar);
#else
  scalar(0, static_cast<size_t>(width));
#endif
}

void threshold(const cv::Mat& src, cv::Mat& dst, int t, std::uint8_t high, cv::Range rows) {
  detail::require_type(src, CV_8UC1, "threshold input");
  detail::require(t >= -1 && t <= 255, "threshold: T must lie in -1..255");
  const cv::Range r = detail::output_rows(dst, src.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) {
    auto* out = dst.ptr<std::uint8_t>(y);
    if (t < 0) {
      std::fill_n(out, src.cols, high);
    } else {
      threshold_row(src.ptr<std::uint8_t>(y), out, src.cols, static_cast<std::uint8_t>(t), high);
    }
  }
}

int otsu_threshold(const Histogram& hist) {
  // Same recurrence and the same floating-point order as OpenCV's getThreshVal_Otsu_8u, so that
  // near-ties resolve identically.
  std::uint64_t total = 0;
  double mu = 0;
  for (int i = 0; i < 256; ++i) {
    total += hist[static_cast<size_t>(i)];
    mu += i * static_cast<double>(hist[static_cast<size_t>(i)]);
  }
  if (total == 0) return 0;
  const double scale = 1.0 / static_cast<double>(total);
  mu *= scale;
  double mu1 = 0;
  double q1 = 0;
  double max_sigma = 0;
  int best = 0;
  for (int i = 0; i < 256; ++i) {
    const double p_i = static_cast<double>(hist[static_cast<size_t>(i)]) * scale;
    mu1 *= q1;
    q1 += p_i;
    const double q2 = 1.0 - q1;
    if (std::min(q1, q2) < FLT_EPSILON || std::max(q1, q2) > 1.0 - FLT_EPSILON) continue;
    mu1 = (mu1 + i * p_i) / q1;
    const double mu2 = (mu - q1 * mu1) / q2;
    const double sigma = q1 * q2 * (mu1 - mu2) * (mu1 - mu2);
    if (sigma > max_sigma) {
      max_sigma = sigma;
      best = i;
    }
  }
  return best;
}

}  // namespace neopipe::kernels
