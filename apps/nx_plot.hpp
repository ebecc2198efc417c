#pragma once
// NX's pictures: the world's marbles, the true Voronoi graph (grey), the learned map (places green,
// edges blue, drawn between where the places really are) and a true track of the tool (red). NX
// follows edges past the world's edges, so the picture shows a margin around the world (dashed
// frame: the world).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rig/nx_system.hpp"
#include "rig/nx_voronoi.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {

/// Writes the PNG; throws UsageError for another extension, std::runtime_error when it cannot write.
void write_nx_plot(const std::string& path, const sim::World& world, const rig::NxExploration& exploration,
                   const rig::VoronoiGraph* truth, const std::vector<Eigen::Vector2d>& track);

}  // namespace neopipe::apps
