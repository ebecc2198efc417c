#pragma once
// The guard both Qualnav levels keep their clearance by: each look's landmarks with their range
// intervals narrowed by the looks before it. One look's intervals are too wide to keep a clearance
// by; since an earlier look the tool moved at most its odometry plus 5 % for the arm's errors, so
// the range then bounds the range now within that.

#include <map>

#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

class RangeGuard {
 public:
  /// `look` fused with the bounds kept so far, at `odometer` mm commanded; the bounds are updated.
  const Viewframe& fuse(const Viewframe& look, double odometer);
  /// The last fused look.
  [[nodiscard]] const Viewframe& guard() const { return guard_; }

 private:
  struct Bound {
    double lo = 0;
    double hi = 0;
    double odometer = 0;  // when they held
  };
  std::map<LandmarkId, Bound> bounds_;
  Viewframe guard_;
};

}  // namespace neopipe::nav::qualnav
