#include "kernels/alu.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <utility>

#include "kernels/rows.hpp"
#include "kernels/simd.hpp"

namespace neopipe::kernels {
namespace {

constexpr std::array<std::pair<AluOp, std::string_view>, 8> kNames{{{AluOp::add, "add"},
                                                                    {AluOp::sub, "sub"},
                                                                    {AluOp::absdiff, "absdiff"},
                                                                    {AluOp::min, "min"},
                                                                    {AluOp::max, "max"},
                                                                    {AluOp::bit_and, "and"},
                                                                    {AluOp::bit_or, "or"},
                                                                    {AluOp::bit_xor, "xor"}}};

// One loop per operation, with the operation known at compile time: `vec` on whole vectors, `f` on
// pixels at the end of short rows.
template <class VecOp, class F>
void each(const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out, int width, [[maybe_unused]] VecOp vec, F f) {
  const auto scalar = [&](size_t x0, size_t x1) {
    for (size_t x = x0; x < x1; ++x) out[x] = static_cast<std::uint8_t>(f(int{a[x]}, int{b[x]}));
  };
#if HWY_TARGET != HWY_SCALAR
  const simd::hn::ScalableTag<std::uint8_t> d;
  simd::point_row(
      d, out, static_cast<size_t>(width),
      [&](size_t x) { return vec(simd::hn::LoadU(d, a + x), simd::hn::LoadU(d, b + x)); }, scalar);
#else
  scalar(0, static_cast<size_t>(width));
#endif
}

}  // namespace

std::string_view to_string(AluOp op) {
  for (const auto& [o, name] : kNames) {
    if (o == op) return name;
  }
  return "?";
}

std::optional<AluOp> alu_op_from_string(std::string_view name) {
  for (const auto& [o, n] : kNames) {
    if (n == name) return o;
  }
  return std::nullopt;
}

void alu_row(AluOp op, const std::uint8_t* a, const std::uint8_t* b, std::uint8_t* out, int width) noexcept {
  namespace hn = simd::hn;
  switch (op) {
    case AluOp::add:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::SaturatedAdd(p, q); },
          [](int p, int q) { return std::min(p + q, 255); });
    case AluOp::sub:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::SaturatedSub(p, q); },
          [](int p, int q) { return std::max(p - q, 0); });
    case AluOp::absdiff:
      // Of the two saturated differences one is |p - q| and the other 0.
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::Or(hn::SaturatedSub(p, q), hn::SaturatedSub(q, p)); },
          [](int p, int q) { return std::abs(p - q); });
    case AluOp::min:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::Min(p, q); }, [](int p, int q) { return std::min(p, q); });
    case AluOp::max:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::Max(p, q); }, [](int p, int q) { return std::max(p, q); });
    case AluOp::bit_and:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::And(p, q); }, [](int p, int q) { return p & q; });
    case AluOp::bit_or:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::Or(p, q); }, [](int p, int q) { return p | q; });
    case AluOp::bit_xor:
      return each(
          a, b, out, width, [](auto p, auto q) { return hn::Xor(p, q); }, [](int p, int q) { return p ^ q; });
  }
}

void alu(AluOp op, const cv::Mat& a, const cv::Mat& b, cv::Mat& dst, cv::Range rows) {
  detail::require_type(a, CV_8UC1, "alu input a");
  detail::require_type(b, CV_8UC1, "alu input b");
  detail::require_same_size(a, b, "alu inputs");
  const cv::Range r = detail::output_rows(dst, a.size(), CV_8UC1, rows);
  for (int y = r.start; y < r.end; ++y) {
    alu_row(op, a.ptr<std::uint8_t>(y), b.ptr<std::uint8_t>(y), dst.ptr<std::uint8_t>(y), a.cols);
  }
}

}  // namespace neopipe::kernels
