// The chain case's iconic stages written in Halide, as a performance-minded user would write them
// (the peer `neopipe bench` measures neopipe's fused executor against): 3x3 smooth
// ([1 2 1; 2 4 2; 1 2 1] / 16, halves rounded up) -> threshold (value > t: 255, else 0) -> 3x3 erode
// -> 3x3 dilate. Each stage replicates its own input's edge, as neopipe's kernels do. For erode and
// dilate that is the same as leaving the outside out, i.e. padding with the operation's neutral
// value (255 for the minimum, 0 for the maximum), which Halide vectorises as a compare where a
// replicated edge costs clamped loads (measured: 4-7x slower per frame at 640x480). Built ahead of
// time by this generator for the host's vector extensions.
//
// Schedule: the output in strips of `strip` rows, strips in parallel; every stage computed per
// strip (with its halo rows) and vectorised across the row; the smooth separable, its horizontal
// pass in 16 bits.

#include "Halide.h"

namespace {

using namespace Halide;

class ChainIconic : public Generator<ChainIconic> {
 public:
  GeneratorParam<int> strip{"strip", 32};
  Input<Buffer<uint8_t>> input{"input", 2};
  Input<uint8_t> threshold{"threshold"};
  Output<Buffer<uint8_t>> output{"output", 2};

  void generate() {
    const Expr w = input.width();
    const Expr h = input.height();
    const Region frame = {{0, w}, {0, h}};

    const Func in = BoundaryConditions::repeat_edge(input);
    across(x, y) = cast<uint16_t>(in(x - 1, y)) + 2 * cast<uint16_t>(in(x, y)) + cast<uint16_t>(in(x + 1, y));
    smooth(x, y) = cast<uint8_t>((across(x, y - 1) + 2 * across(x, y) + across(x, y + 1) + 8) >> 4);
    binary(x, y) = select(smooth(x, y) > threshold, cast<uint8_t>(255), cast<uint8_t>(0));

    const Func b = BoundaryConditions::constant_exterior(binary, cast<uint8_t>(255), frame);
    erode_across(x, y) = min(b(x - 1, y), min(b(x, y), b(x + 1, y)));
    eroded(x, y) = min(erode_across(x, y - 1), min(erode_across(x, y), erode_across(x, y + 1)));

    const Func e = BoundaryConditions::constant_exterior(eroded, cast<uint8_t>(0), frame);
    dilate_across(x, y) = max(e(x - 1, y), max(e(x, y), e(x + 1, y)));
    output(x, y) = max(dilate_across(x, y - 1), max(dilate_across(x, y), dilate_across(x, y + 1)));
  }

  void schedule() {
    const int lanes = natural_vector_size<uint8_t>();
    // Intermediate stages round their rows up to whole vectors (they have the room); the output
    // shifts its last vector inward where the frame is at least a vector wide, else guards it, and
    // guards the last strip: any frame size, down to 1 x 1.
    const Expr wide = output.dim(0).extent() >= lanes;
    output.split(y, yo, yi, strip, TailStrategy::GuardWithIf).parallel(yo);
    output.specialize(wide).vectorize(x, lanes, TailStrategy::ShiftInwards);
    output.vectorize(x, lanes, TailStrategy::GuardWithIf);
    for (Func* f : {&smooth, &binary, &erode_across, &eroded, &dilate_across}) {
      f->compute_at(output, yo).vectorize(x, lanes, TailStrategy::RoundUp);
    }
    across.compute_at(output, yo).vectorize(x, lanes / 2, TailStrategy::RoundUp);  // 16-bit sums
  }

 private:
  Var x{"x"}, y{"y"}, yo{"yo"}, yi{"yi"};
  Func across{"across"}, smooth{"smooth"}, binary{"binary"};
  Func erode_across{"erode_across"}, eroded{"eroded"}, dilate_across{"dilate_across"};
};

}  // namespace

HALIDE_REGISTER_GENERATOR(ChainIconic, neopipe_chain_iconic)
