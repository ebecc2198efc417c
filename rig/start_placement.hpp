#pragma once
// Where the harness puts the tool at a journey's start for the systems that travel among the marbles
// rather than over them (QRM, Qualnav): beside the start object, in its Voronoi cell, clear of every
// marble. The truth is used here, as the harness's job; the system gets only the offset.

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "sim/world.hpp"

namespace neopipe::rig {

/// The nearest point to object `id` on rings round it (every 5 mm, every 15°, first direction
/// first: deterministic) that keeps sim::kMinClearanceMm + `margin` from every marble's surface and
/// is nearer `id` than any other marble by 2 · `margin`; its offset from the object, or none within
/// 40 mm of the first ring.
std::optional<Eigen::Vector2d> clear_start_offset(const sim::World& world, std::uint32_t id, double margin);

}  // namespace neopipe::rig
