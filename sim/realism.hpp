#pragma once
// Realism presets: how close the simulated rig is to a real one.
//   ideal  today's images: flat disks, OpenCV's lens, an illumination gradient, Gaussian noise
//          (what the project's own models assume: they fit these images exactly)
//   rig    spheres under a point light above a workspace corner (shading, highlight, shadow), a
//          textured table, a lens beyond OpenCV's model, vignetting, defocus growing towards the
//          corners, shot and read noise and PRNU: what a real rig would show, still easy to segment
//   harsh  all of it stronger: a closer light, a brighter (saturating) highlight, more distortion,
//          defocus and noise, and interlaced frames
// docs/simulator.md has the table of every parameter per preset.

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "sim/cameras.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

enum class Realism { ideal, rig, harsh };
enum class CameraKind { global, onboard };

/// "ideal", "rig" or "harsh"; throws std::invalid_argument naming `text` otherwise.
Realism parse_realism(std::string_view text);
std::string realism_name(Realism r);

/// The preset's settings for one camera of a rig over a W x H mm workspace (the light hangs
/// above its north-west corner). Validated.
Rendering rendering_for(Realism realism, CameraKind camera, const Eigen::Vector2d& workspace = {500, 500});

/// The onboard camera for these settings and marbles of `marble_diameter`: spheres put the view
/// window in the plane of their centres (OnboardCameraConfig::window_plane_z); disks keep it on the
/// table. The other fields are `base`'s.
OnboardCameraConfig onboard_config_for(const Rendering& rendering, double marble_diameter,
                                       OnboardCameraConfig base = {});

}  // namespace neopipe::sim
