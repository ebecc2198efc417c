#pragma once
// `neopipe sim render` and `neopipe sim video`: camera frames of a world, with the truth.

#include "apps/sim_command.hpp"

namespace neopipe::apps {

void add_sim_camera_options(CLI::App& cmd, SimCameraArgs& args);
int sim_render_command(const SimRenderArgs& args);
int sim_video_command(const SimVideoArgs& args);

}  // namespace neopipe::apps
