#pragma once
// The map-maker's survey of a simulated world: where it believes the objects are. Either through the
// rig, as the paper's system did it (global camera image -> the engine's marble graph -> a
// calibration from rendered dot-grid views -> workspace millimetres), or by moving the true
// positions by a chosen Gaussian error (the experiments on sensor accuracy). It needs the world's
// truth to render the images and to give each surveyed object its world id; what it hands on (the
// workspace and the told sigma) carries no truth.

#include <cstdint>
#include <stdexcept>
#include <string>

#include "nav/mapmaker/workspace.hpp"
#include "sim/world.hpp"

namespace neopipe::rig {

/// The survey could not be made (marbles the image cannot separate, a target not found).
class SurveyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Survey {
  nav::mapmaker::Workspace workspace;  ///< object ids are the world's
  std::string method;                  ///< "global_camera" or "gaussian"
  /// The position error the map-maker is told (sd per axis, mm): the calibration's held-out sd
  /// (larger axis) for the camera, the chosen sigma for the Gaussian survey.
  double sigma = 0;
  /// Measured against the world's truth (the rig may; the map-maker never sees this): RMS and
  /// largest length of surveyed minus true position, mm.
  double rms_error = 0;
  double max_error = 0;
};

/// Every object moved by N(0, sigma) per axis (seeded), kept on the workspace.
Survey gaussian_survey(const sim::World& world, double sigma, std::uint64_t seed);

/// The rig's survey: the default global camera (sim/cameras.hpp: tilted, lens distortion, noise)
/// calibrated from five rendered views of a 15 x 15 dot grid (the first flat on the workspace), then
/// one image of the world through the engine's marble graph, mapped to the workspace. Throws
/// SurveyError when the image does not show every marble as one blob (marbles touching in the
/// global camera's pixels), naming the objects, or when the target is not found.
Survey global_camera_survey(const sim::World& world, std::uint64_t seed);

}  // namespace neopipe::rig
