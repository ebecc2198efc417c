#pragma once
// A viewframe (qualnav.md §3; seed 003 §2): what one panorama tells about the landmarks in view —
// their ids in pan order, bearings, bearing errors and range intervals — and the compass bearing
// of the sensor when it was taken. Angles between landmarks do not depend on the tool's heading, so
// two viewframes taken at different headings compare directly; the compass relates them to the
// world when a heading must be turned into a move.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace neopipe::nav::qualnav {

// The same alias as the topology level's (nav/qualnav/topology/lpb.hpp), so both may be included.
using LandmarkId = std::size_t;

struct ViewedLandmark {
  LandmarkId id = 0;
  double bearing = 0;   ///< rad in [0, 2π), counter-clockwise from the sensor's (tool's) +x axis
  double error = 0;     ///< rad: the bearing is within this of the truth
  double range = 0;     ///< mm, the sensor's estimate d̂
  double range_lo = 0;  ///< mm: the true range is in [range_lo, range_hi]
  double range_hi = 0;  ///< mm
  [[nodiscard]] double range_mid() const { return (range_lo + range_hi) / 2; }
};

struct Viewframe {
  /// In pan order: clockwise from the sensor's +x axis (decreasing counter-clockwise bearing).
  std::vector<ViewedLandmark> landmarks;
  double compass = 0;  ///< rad: the sensor's +x axis counter-clockwise from the world's +x axis

  [[nodiscard]] const ViewedLandmark* find(LandmarkId id) const;
  [[nodiscard]] bool sees(LandmarkId id) const { return find(id) != nullptr; }
};

/// Puts `landmarks` in pan order (one entry per id: the first of duplicates is kept).
Viewframe make_viewframe(std::vector<ViewedLandmark> landmarks, double compass);

/// The angle in (−π, π] wrapped from any angle.
double wrap_angle(double a);

/// Ang_ij: the signed counter-clockwise angle from landmark i's bearing to j's, (−π, π].
double angle_between(const ViewedLandmark& i, const ViewedLandmark& j);

/// The ids two viewframes both see, ascending.
std::vector<LandmarkId> shared_landmarks(const Viewframe& a, const Viewframe& b);

}  // namespace neopipe::nav::qualnav
