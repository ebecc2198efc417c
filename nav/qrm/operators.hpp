#pragma once
// The unary operators of Table I (spec qrm.md §3), on states and on sets of states:
// L (left shift) AB:C -> BC:A, R (right shift) AB:C -> CA:B, I (inverse) AB:C -> BA:C.

#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

StateSet left_shift(State s);
StateSet right_shift(State s);
State inverse(State s);  ///< 21 - s

/// Op(S) = union of Op(s) over s in S.
StateSet left_shift(StateSet set);
StateSet right_shift(StateSet set);
/// I on a set: bit s -> bit 21 - s, a bit reversal.
constexpr StateSet inverse(StateSet set) {
  StateSet::Mask m = set.mask();
  // Reverse all 32 bits, then bit s sits at 31 - s; shifting by 10 puts it at 21 - s.
  m = ((m >> 1) & 0x55555555U) | ((m & 0x55555555U) << 1);
  m = ((m >> 2) & 0x33333333U) | ((m & 0x33333333U) << 2);
  m = ((m >> 4) & 0x0F0F0F0FU) | ((m & 0x0F0F0F0FU) << 4);
  m = ((m >> 8) & 0x00FF00FFU) | ((m & 0x00FF00FFU) << 8);
  m = (m >> 16) | (m << 16);
  return StateSet::from_mask(m >> 10);
}

}  // namespace neopipe::nav::qrm
