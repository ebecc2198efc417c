#pragma once
// The control laws of orientation headings (qualnav.md §6, Decision): which way the robot steers for
// a heading x[P Q] reduced by the productions of §5 (nav/qualnav/topology/productions.hpp gives the
// specifier; its Specifier l, b, r, a map one to one onto OrientationKind here):
//   b — along the bisector of P's and Q's bearings (between them: crosses the LPB between P and Q);
//   l — at P turned 10° away from Q (passes P on the side away from Q: crosses beyond P);
//   r — mirrored: at Q turned 10° away from P;
//   a — at P (the caller stops at 15 mm).
// Bearings are in the sensor frame; P is left of Q as the productions write pairs (the pair seen
// within 180°, P counter-clockwise of Q from the robot).

#include <cstdint>
#include <optional>

#include "nav/qualnav/metric/viewframe.hpp"

namespace neopipe::nav::qualnav {

enum class OrientationKind : std::uint8_t { l, b, r, a };

inline constexpr double kOrientationTurn = 10 * 3.14159265358979323846 / 180;  ///< l and r: 10°

/// The sensor bearing to steer for kind[P Q] in `view`; nullopt when P (or, for b, l and r, Q) is not
/// in view.
std::optional<double> orientation_heading(OrientationKind kind, LandmarkId p, LandmarkId q, const Viewframe& view);

}  // namespace neopipe::nav::qualnav
