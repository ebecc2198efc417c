#include "nav/qrm/operators.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace neopipe::nav::qrm {
namespace {

// Table I, index = state.
constexpr std::array<StateSet, kStateCount + 1> kLeft{
    StateSet{},     StateSet{17},    StateSet{18}, StateSet{19}, StateSet{20}, StateSet{12}, StateSet{11},
    StateSet{1, 5}, StateSet{2, 10}, StateSet{16}, StateSet{15}, StateSet{13}, StateSet{7},  StateSet{3, 6},
    StateSet{4, 9}, StateSet{8},     StateSet{14}, StateSet{7},  StateSet{8},  StateSet{13}, StateSet{14}};
constexpr std::array<StateSet, kStateCount + 1> kRight{
    StateSet{},       StateSet{7},      StateSet{8},  StateSet{13}, StateSet{14}, StateSet{7}, StateSet{13},
    StateSet{12, 17}, StateSet{15, 18}, StateSet{14}, StateSet{8},  StateSet{6},  StateSet{5}, StateSet{11, 19},
    StateSet{16, 20}, StateSet{10},     StateSet{9},  StateSet{1},  StateSet{2},  StateSet{3}, StateSet{4}};

}  // namespace

StateSet left_shift(State s) {
  check_state(s);
  return kLeft[s];
}

StateSet right_shift(State s) {
  check_state(s);
  return kRight[s];
}

State inverse(State s) {
  check_state(s);
  return kStateCount + 1 - s;
}

StateSet left_shift(StateSet set) {
  StateSet out;
  for (const State s : set) out |= kLeft[s];
  return out;
}

StateSet right_shift(StateSet set) {
  StateSet out;
  for (const State s : set) out |= kRight[s];
  return out;
}

}  // namespace neopipe::nav::qrm
