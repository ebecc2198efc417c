#pragma once
// An arm sized for a workspace: the world file gives the workspace, the arm must reach all of it.

#include <Eigen/Core>

#include "sim/arm/scara.hpp"

namespace neopipe::sim {

/// A geometry that reaches every point of the workspace [0, W] x [0, H] mm and a margin of
/// m = 0.05 s around it (s = max(W, H)), with any tool heading, in one elbow configuration and
/// within the default joint limits (those of ScaraGeometry{}):
///   base    = (W/2, -m - 0.2 s): centred, standing 0.2 s South of the margin's edge;
///   l1 = l2 = 0.525 R rounded up to a multiple of s/20, R = distance to the margin's far corners.
/// Why this always works: stretched to the 1 deg elbow limit the arm reaches 2 L cos(0.5 deg) >= 1.05 R;
/// folded to 170 deg it comes in to 2 L cos(85 deg) <= 0.14 s, inside the nearest point (0.2 s away);
/// every bearing from the base into the box lies in (0, 180) deg and equal links put the shoulder
/// q2/2 <= 85 deg clockwise of the bearing, within -90..180 deg. For 500 x 500 this is exactly
/// ScaraGeometry{}. Throws std::invalid_argument unless W and H are positive and finite.
ScaraGeometry scara_for_workspace(const Eigen::Vector2d& size);

}  // namespace neopipe::sim
