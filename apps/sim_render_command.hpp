#pragma once
// `neopipe sim render` and `neopipe sim video`: camera frames of a world, with the truth.

#include <Eigen/Core>

#include "apps/sim_command.hpp"
#include "sim/realism.hpp"

namespace neopipe::apps {

/// The camera, realism and effect options of `sim render` and `sim video` (defined in sim_command.cpp).
void add_sim_camera_options(CLI::App& cmd, SimCameraArgs& args);
/// The preset named by --realism for `kind` over `workspace`, with the effect options applied and
/// validated (errors name the option).
sim::Rendering rendering_of(const SimCameraArgs& args, sim::CameraKind kind, const Eigen::Vector2d& workspace);
int sim_render_command(const SimRenderArgs& args);
int sim_video_command(const SimVideoArgs& args);

}  // namespace neopipe::apps
