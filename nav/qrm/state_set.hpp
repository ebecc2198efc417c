#pragma once
// The 20 states of the extended double cross (EDC, spec qrm.md §2) and sets of them as 20-bit masks:
// bit s stands for state s, so a set fits a register and the map's updates are bitwise.

#include <bit>
#include <cstdint>
#include <initializer_list>
#include <iosfwd>
#include <iterator>
#include <string>

namespace neopipe::nav::qrm {

/// An EDC state, 1..20 in the numbering of spec §2; 0 means "degenerate" where a classifier returns it.
using State = int;
inline constexpr int kStateCount = 20;

/// A set of EDC states.
class StateSet {
 public:
  using Mask = std::uint32_t;
  /// Bits 1..20; bit 0 is never set (state 0 is not a state).
  static constexpr Mask kAllMask = ((Mask{1} << (kStateCount + 1)) - 1) & ~Mask{1};

  /// Visits the states in increasing order.
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = State;
    using difference_type = std::ptrdiff_t;
    using pointer = const State*;
    using reference = State;
    constexpr Iterator() = default;
    constexpr explicit Iterator(Mask rest) : rest_(rest) {}
    constexpr State operator*() const { return std::countr_zero(rest_); }
    constexpr Iterator& operator++() {
      rest_ &= rest_ - 1;
      return *this;
    }
    constexpr Iterator operator++(int) {
      const Iterator before = *this;
      ++*this;
      return before;
    }
    constexpr bool operator==(const Iterator&) const = default;

   private:
    Mask rest_ = 0;
  };

  constexpr StateSet() = default;
  constexpr StateSet(std::initializer_list<State> states) {
    for (const State s : states) insert(s);
  }
  /// Bits outside 1..20 are dropped.
  static constexpr StateSet from_mask(Mask mask) {
    StateSet set;
    set.mask_ = mask & kAllMask;
    return set;
  }
  static constexpr StateSet all() { return from_mask(kAllMask); }
  /// {from, from + 1, ..., to}.
  static constexpr StateSet range(State from, State to) {
    StateSet set;
    for (State s = from; s <= to; ++s) set.insert(s);
    return set;
  }

  constexpr Mask mask() const { return mask_; }
  constexpr bool contains(State s) const { return s >= 1 && s <= kStateCount && ((mask_ >> s) & 1U) != 0; }
  constexpr int count() const { return std::popcount(mask_); }
  constexpr bool empty() const { return mask_ == 0; }
  constexpr bool is_all() const { return mask_ == kAllMask; }
  /// The only state of a singleton, else 0.
  constexpr State single() const { return count() == 1 ? std::countr_zero(mask_) : 0; }
  /// States 1..20 only; anything else is ignored.
  constexpr void insert(State s) {
    if (s >= 1 && s <= kStateCount) mask_ |= Mask{1} << s;
  }
  constexpr bool subset_of(StateSet other) const { return (mask_ & ~other.mask_) == 0; }

  constexpr Iterator begin() const { return Iterator(mask_); }
  constexpr Iterator end() const { return Iterator(0); }

  constexpr StateSet operator|(StateSet o) const { return from_mask(mask_ | o.mask_); }
  constexpr StateSet operator&(StateSet o) const { return from_mask(mask_ & o.mask_); }
  constexpr StateSet& operator|=(StateSet o) {
    mask_ |= o.mask_;
    return *this;
  }
  constexpr StateSet& operator&=(StateSet o) {
    mask_ &= o.mask_;
    return *this;
  }
  constexpr bool operator==(const StateSet&) const = default;

  /// "{1,5,11}"; "{}" for the empty set.
  std::string to_string() const;

 private:
  Mask mask_ = 0;
};

std::ostream& operator<<(std::ostream& out, StateSet set);

/// Throws std::out_of_range unless 1 <= s <= 20: the operators and tables take single states.
void check_state(State s);

}  // namespace neopipe::nav::qrm
