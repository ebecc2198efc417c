#include "nav/qualnav/navigator/range_guard.hpp"

#include <algorithm>

namespace neopipe::nav::qualnav {

const Viewframe& RangeGuard::fuse(const Viewframe& look, double odometer) {
  guard_ = look;
  for (ViewedLandmark& l : guard_.landmarks) {
    auto [it, fresh] = bounds_.try_emplace(l.id, Bound{l.range_lo, l.range_hi, odometer});
    if (!fresh) {
      const double moved = 1.05 * (odometer - it->second.odometer) + 0.1;
      const double lo = std::max(l.range_lo, it->second.lo - moved);
      const double hi = std::min(l.range_hi, it->second.hi + moved);
      if (lo <= hi) {  // else the looks disagree: the new one stands alone
        l.range_lo = lo;
        l.range_hi = hi;
      }
    }
    it->second = Bound{l.range_lo, l.range_hi, odometer};
  }
  return guard_;
}

}  // namespace neopipe::nav::qualnav
