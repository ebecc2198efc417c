#pragma once
// What the Highway kernels share: the row loops that cut a row into whole vectors and cover its
// end. Highway is used with static dispatch: every kernel is compiled for the one target the
// compile flags allow (AVX2 under -march=native on an x86-64 with it), with no runtime choice.
//
// Highway's HWY_SCALAR target (a build for plain x86-64 without -march=native, for instance) has
// one-lane vectors, too narrow for the byte shuffles and the even/odd byte splits the kernels use:
// there the kernels keep their scalar loops, behind `#if HWY_TARGET != HWY_SCALAR`.

#include <hwy/highway.h>

#include <bit>
#include <cstddef>

namespace neopipe::kernels::simd {

namespace hn = hwy::HWY_NAMESPACE;

// The kernels split 16-bit lanes into their even (low) and odd (high) bytes, i.e. pixels x and
// x + 1; that is the memory order only on a little-endian machine.
static_assert(std::endian::native == std::endian::little, "the SIMD kernels assume little-endian lanes");

/// A point kernel's row: `vec(x)` returns the output vector for pixels [x, x + Lanes(d)) and
/// `scalar(x0, x1)` computes pixels [x0, x1) one at a time; it covers rows shorter than a vector.
/// A row that is not a whole number of vectors ends with one vector moved back to end at the last
/// pixel. That vector is computed before the loop and stored after it, so a kernel run in place
/// (out == in) reads only original pixels, as its scalar loop would.
template <class D, class VecFn, class ScalarFn>
HWY_INLINE void point_row(D d, hn::TFromD<D>* out, std::size_t width, VecFn&& vec, ScalarFn&& scalar) {
  const std::size_t n = hn::Lanes(d);
  if (width < n) {
    scalar(std::size_t{0}, width);
    return;
  }
  std::size_t x = 0;
  if (width % n == 0) {
    for (; x < width; x += n) hn::StoreU(vec(x), d, out + x);
    return;
  }
  const auto last = vec(width - n);
  for (; x + n <= width; x += n) hn::StoreU(vec(x), d, out + x);
  hn::StoreU(last, d, out + width - n);
}

/// The interior of a 3x3 kernel's row, pixels [1, width - 1): `block(x)` computes and stores
/// output pixels [x, x + n), reading input pixels x - 1 .. x + n; `scalar(x0, x1)` covers rows
/// whose interior is shorter than n. The last block overlaps the one before it, which is harmless:
/// a neighbourhood kernel's output never shares memory with its input.
template <class BlockFn, class ScalarFn>
HWY_INLINE void interior_blocks(std::size_t width, std::size_t n, BlockFn&& block, ScalarFn&& scalar) {
  if (width < n + 2) {
    if (width > 2) scalar(std::size_t{1}, width - 1);
    return;
  }
  const std::size_t end = width - 1;
  std::size_t x = 1;
  for (; x + n <= end; x += n) block(x);
  if (x != end) block(end - n);
}

}  // namespace neopipe::kernels::simd
