#pragma once
// The rig's random streams. One experiment seed feeds many consumers (the survey's images, the
// start/goal draws, each journey's arm and camera); each takes its own stream, so changing how
// many numbers one draws never shifts another's.

#include <cstdint>

namespace neopipe::rig {

/// Independent stream `stream` of `seed`.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream);

/// The seed of trial `index` in a run seeded by `seed`.
std::uint64_t trial_seed(std::uint64_t seed, std::int64_t index);

/// The streams the rig uses, by number (kept stable: published figures depend on them).
namespace streams {
inline constexpr std::uint64_t arm = 0;                ///< a journey's arm errors
inline constexpr std::uint64_t onboard_camera = 1;     ///< a journey's onboard camera noise
inline constexpr std::uint64_t panorama = 2;           ///< a journey's panoramic sensor (bearings, compass)
inline constexpr std::uint64_t range_ring = 3;         ///< a journey's range ring (ranges, compass)
inline constexpr std::uint64_t gaussian_survey = 100;  ///< the Gaussian survey's errors
inline constexpr std::uint64_t global_camera = 101;    ///< the global camera's noise (survey, calibration)
inline constexpr std::uint64_t qrm_positions = 200;    ///< QRM map building: the imaging positions
inline constexpr std::uint64_t qrm_headings = 201;     ///< QRM map building: the sensor's zero direction per image
inline constexpr std::uint64_t qrm_world = 202;        ///< a QRM Monte Carlo run's world
}  // namespace streams

}  // namespace neopipe::rig
