#pragma once
// Viewframe headings (qualnav.md §3; seed 003 §2): the move from where one viewframe was taken to
// where another was, in a frame both can be localized in.
//
// Decision: the frame is the shared pair of widest separation below 180° (in both viewframes), L1 =
// (0,0), L2 = (s,0) with L1 the pair's first landmark in counter-clockwise order; s from the law of
// cosines on the range intervals' midpoints, averaged over the viewframes that share the pair (a
// FrameScales collects them). h = c2 − c1 between the two centroids; |h| estimates the distance;
// the sensor bearing of the move is atan2(h) + β_p − atan2(L_p − c1), averaged over p = L1, L2.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "nav/qualnav/metric/localization.hpp"
#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

/// An unordered landmark pair, smaller id first.
using PairKey = std::pair<LandmarkId, LandmarkId>;
PairKey make_pair_key(LandmarkId a, LandmarkId b);

/// s² = m_i² + m_j² − 2·m_i·m_j·cos Ang_ij on the interval midpoints; nullopt unless `view` sees both.
std::optional<double> pair_separation(const Viewframe& view, PairKey pair);

/// The frame's s of each pair, averaged over the viewframes added.
class FrameScales {
 public:
  void add(const Viewframe& view);
  /// The average s of `pair`, or nullopt when no viewframe added saw it.
  [[nodiscard]] std::optional<double> scale(PairKey pair) const;

 private:
  std::map<PairKey, std::pair<double, int>> sums_;
};

/// The frame of a pair: L1 = (0,0), L2 = (s,0). `first` is L1.
struct PairFrame {
  LandmarkId first = 0;
  LandmarkId second = 0;
  double s = 0;
  [[nodiscard]] FramePositions positions() const;
};

/// Decision: the shared pair of widest separation below 180° in both viewframes (the smaller of the
/// two separations decides; ties: lower ids). L1 is the landmark from which the other lies
/// counter-clockwise in `a` (within π). nullopt when they share fewer than two landmarks or no pair
/// is separated by less than `max_separation` in both.
/// Every pair choose_frame considers, widest first (choose_frame returns the first).
std::vector<PairFrame> candidate_frames(const Viewframe& a, const Viewframe& b, const FrameScales& scales,
                                        double max_separation = 179.0 * 3.14159265358979323846 / 180);
std::optional<PairFrame> choose_frame(const Viewframe& a, const Viewframe& b, const FrameScales& scales,
                                      double max_separation = 179.0 * 3.14159265358979323846 / 180);

struct ViewframeHeading {
  PairFrame frame;
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< c1, the centroid of the first viewframe's region
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< c2
  Eigen::Vector2d h = Eigen::Vector2d::Zero();     ///< c2 − c1, in the frame
  double distance = 0;                             ///< |h|, mm
  double sensor_bearing = 0;                       ///< rad, counter-clockwise in the first viewframe's sensor frame
};

/// Localizes a viewframe in a pair frame: exactly, then with the bearing errors widened fourfold,
/// then without the ranges (when the intervals and the averaged s disagree). Empty if all fail.
Localization localize_in_frame(const Viewframe& view, const PairFrame& frame, const LocalizationOptions& options = {});

/// The bearing of a frame vector `v` in `view`'s sensor frame, from where `view` was localized (c).
double sensor_bearing_of(const Viewframe& view, const PairFrame& frame, const Eigen::Vector2d& c,
                         const Eigen::Vector2d& v);

/// The heading from `from` to `to` (nullopt: no frame, or a viewframe not localized).
std::optional<ViewframeHeading> viewframe_heading(const Viewframe& from, const Viewframe& to, const FrameScales& scales,
                                                  const LocalizationOptions& options = {});

}  // namespace neopipe::nav::qualnav
