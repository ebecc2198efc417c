#pragma once
// Landmark-pair boundaries (spec qualnav.md §4; seed 003 §2). LPB(L1, L2) is the whole line through
// the two landmarks, split into l (beyond L1), b (between) and r (beyond L2). An observer's side of
// it is the pair's orientation, read from two bearings of a panorama or, for the harness and the
// tests, from world positions. The spec's cases rule over the scan's leading minus (§11).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

namespace neopipe::nav::qualnav {

/// A landmark's identity: its index in the world (the panorama's blob value − 1).
using LandmarkId = std::size_t;

/// The ordered pair (L1, L2) of an LPB. Its orientation flips with the order.
struct LandmarkPair {
  LandmarkId first = 0;   ///< L1
  LandmarkId second = 0;  ///< L2
  friend bool operator==(const LandmarkPair&, const LandmarkPair&) = default;
  friend bool operator<(const LandmarkPair& a, const LandmarkPair& b) {
    return std::tie(a.first, a.second) < std::tie(b.first, b.second);
  }
};

/// The part of LPB(L1, L2) a point on its line lies in.
enum class LpbPart : std::uint8_t {
  l,  ///< beyond L1 (L1 hides L2)
  b,  ///< between L1 and L2 (they appear 180° apart)
  r   ///< beyond L2 (L2 hides L1)
};

/// 'l', 'b' or 'r'.
char part_letter(LpbPart part);

/// Θ12 = (β1 − β2) mod 2π in [0, 2π): the clockwise (pan) angle from L1 to L2, for counter-clockwise
/// bearings β1 and β2 in radians (any range).
double pan_angle(double bearing1, double bearing2);

/// The orientation of (L1, L2) seen from bearings β1, β2 (counter-clockwise, radians): +1 if
/// Θ12 < π (the observer is on side [L1 L2]), −1 if Θ12 > π, 0 if |Θ12 − π| <= tolerance (radians).
int orientation_from_bearings(double bearing1, double bearing2, double tolerance = 0.0);

/// The orientation of (L1, L2) seen from `observer`: +1 ⇔ cross(L1 − O, L2 − O) < 0, −1 if > 0, 0 on
/// the line (|cross| <= tolerance · |L1 − O| · |L2 − O|, i.e. tolerance is the sine of the angle).
int orientation_from_positions(const Eigen::Vector2d& l1, const Eigen::Vector2d& l2, const Eigen::Vector2d& observer,
                               double tolerance = 0.0);

/// The part of LPB(L1, L2) the point `on_line` (assumed on the line) lies in, by its projection
/// t = (P − L1)·(L2 − L1)/|L2 − L1|²: l for t < 0, r for t > 1, else b. L1 == L2 is invalid_argument.
LpbPart part_of_line(const Eigen::Vector2d& l1, const Eigen::Vector2d& l2, const Eigen::Vector2d& on_line);

/// The part of LPB(L1, L2) a crossing went through, the crossing seen as a sign flip between two
/// frames (spec §4 Decision): b if the pair's separation in the frame before the flip exceeds 90°,
/// else l if L1 was nearer (range1 < range2), else r. Bearings in radians, ranges in any one unit.
LpbPart classify_crossing(double bearing1_before, double bearing2_before, double range1_before, double range2_before);

/// One orientation per pair: +1, 0 or −1.
using SignVector = std::vector<std::int8_t>;

/// The orientations of `pairs` seen from `observer`, `landmarks` indexed by LandmarkId. A pair naming
/// a landmark outside `landmarks` is std::out_of_range.
SignVector sign_vector(std::span<const Eigen::Vector2d> landmarks, std::span<const LandmarkPair> pairs,
                       const Eigen::Vector2d& observer, double tolerance = 0.0);

/// A landmark seen in a panorama: its id and its counter-clockwise bearing (radians).
struct Sighting {
  LandmarkId id = 0;
  double bearing = 0;
};

/// The orientations of `pairs` from the sightings of one panorama; a pair with a landmark not in
/// `seen` is std::invalid_argument naming it.
SignVector sign_vector_from_bearings(std::span<const Sighting> seen, std::span<const LandmarkPair> pairs,
                                     double tolerance = 0.0);

/// Every pair (i, j), i < j, of `ids` (in the order given), the LPBs of a set of landmarks.
std::vector<LandmarkPair> all_pairs(std::span<const LandmarkId> ids);

}  // namespace neopipe::nav::qualnav
