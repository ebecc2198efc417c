#pragma once
// `neopipe qrm build --plot`: the world's landmarks, the true RNG and the RNG estimated from the
// map, and the imaging positions, as a PNG drawn by OpenCV.

#include <string>

#include "rig/qrm_build.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {

/// Writes the picture of `result` (its final map) over `world` to `path` (.png).
void write_qrm_build_plot(const sim::World& world, const rig::QrmBuildResult& result, const std::string& path);

}  // namespace neopipe::apps
