#pragma once
// Vocabulary shared by every kernel: what a kernel reads around an output pixel (its footprint)
// and what it sees beyond the image edge (its border).

#include <cstdint>
#include <stdexcept>
#include <string>

namespace neopipe::kernels {

/// How far a kernel reaches around an output pixel. The scheduler cuts frames into stripes of rows
/// from this: a point kernel needs only its own rows, a 3x3 kernel one extra row above and below,
/// and a frame kernel (histogram, blob extraction) needs the whole frame at once.
enum class Footprint { point, neighbourhood3x3, frame };

/// Rows of input a kernel reads above and below each output row.
constexpr int halo_rows(Footprint f) {
  return f == Footprint::neighbourhood3x3 ? 1 : 0;
}

/// What a neighbourhood kernel sees outside the image.
///  - replicate: the nearest edge pixel (OpenCV's BORDER_REPLICATE). For erode and dilate this is
///    the same as OpenCV's default morphology border, so results equal cv::erode / cv::dilate.
///  - constant: a fixed value (for Boolean kernels, any non-zero value means "set").
enum class BorderMode { replicate, constant };

struct Border {
  BorderMode mode = BorderMode::replicate;
  int value = 0;
};

/// Thrown when a kernel is called with images it cannot process (wrong type, mismatched sizes).
class KernelError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace neopipe::kernels
