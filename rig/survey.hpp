#pragma once
// The map-maker's survey of a simulated world: where it believes the objects are. Either through the
// rig, as the paper's system did it (global camera image -> the engine's marble graph -> a
// calibration from rendered dot-grid views -> workspace millimetres), or by moving the true
// positions by a chosen Gaussian error (the experiments on sensor accuracy). It needs the world's
// truth to render the images and to give each surveyed object its world id; what it hands on (the
// workspace and the told sigma) carries no truth.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "nav/mapmaker/workspace.hpp"
#include "rig/global_camera.hpp"
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
  std::string realism;                 ///< the global camera's ("" for the Gaussian survey)
  /// The position error the map-maker is told (sd per axis, mm): for the camera, what its session
  /// measured on marbles at known places (GlobalCameraSession::told_sigma); the chosen sigma for
  /// the Gaussian survey.
  double sigma = 0;
  std::optional<GlobalCameraSession> session;  ///< the camera's calibration session
  /// Measured against the world's truth (the rig may; the map-maker never sees this): RMS and
  /// largest length of surveyed minus true position, mm.
  double rms_error = 0;
  double max_error = 0;
};

/// Every object moved by N(0, sigma) per axis (seeded), kept on the workspace.
Survey gaussian_survey(const sim::World& world, double sigma, std::uint64_t seed);

struct SurveySettings {
  GlobalCameraSettings camera;  ///< realism, pose, board, seed
  /// Where calibration sessions are cached (CalibrationCache::default_dir() for the usual place);
  /// none: calibrate every time.
  std::optional<std::filesystem::path> cache_dir;
  std::function<void(const std::string&)> note;  ///< hears one line per corrupt cache entry
};

/// The rig's survey: the global camera's calibration session (rig/global_camera.hpp; cached), then
/// one image of the world through the engine's marble graph, each weighted centroid corrected for
/// the lean the session measured and mapped to the workspace at the marbles' centre height. Throws
/// SurveyError when the image does not show every marble as one blob (marbles touching in the
/// global camera's pixels), naming the objects, or when the session fails.
Survey global_camera_survey(const sim::World& world, const SurveySettings& settings);

/// The session for this world's workspace and marbles, from the cache when it has it.
GlobalCameraSession global_camera_session(const sim::World& world, const SurveySettings& settings);

}  // namespace neopipe::rig
