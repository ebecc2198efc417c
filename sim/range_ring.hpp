#pragma once
// NX's range-ring sensor in the dots world (qualnav.md §9): a ring of 16 range sensors, 22.5° apart,
// each reporting the nearest marble within its reach, with a relative error; and a compass.
//
// Decisions (the paper's sonar ring restated for point-like marbles):
// - Sector k (0..15) looks at bearing k · 22.5°, counter-clockwise from the tool's +x axis, and
//   covers bearings [k · 22.5° − 11.25°, k · 22.5° + 11.25°). A marble belongs to the sector that
//   holds the bearing of its centre; the sector reports the nearest of its marbles.
// - A range is the distance from the tool to the marble's surface (centre distance − radius), as a
//   sonar measures the nearest obstacle; it is reported when it is at most `range_mm` (150 mm).
// - Error: the reading is multiplied by 1 + e, e uniform in [−relative_error, +relative_error]
//   (the paper's "random error <= 10 percent"), one draw per sector and frame; 0 turns it off.
// - A frame is 1 x 16 CV_32FC1, column k sector k; 0 means nothing in range (or the tool inside a
//   marble). It travels through the rig's frame source like the cameras' images.
// - The compass reads the tool's heading with a Gaussian error (σ = 1° by default).

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>

#include "pipeline/io/frame_source.hpp"
#include "sim/pose2.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace neopipe::sim {

inline constexpr int kRangeSectors = 16;
inline constexpr double kRangeSectorDeg = 22.5;

struct RangeRingSettings {
  double range_mm = 150;         ///< a sector sees marbles whose surface lies within this
  double relative_error = 0.10;  ///< bound of the uniform relative error; 0: exact ranges
  double compass_sigma_deg = 1;  ///< sd of the compass's error
  std::uint64_t seed = 1;        ///< the range and compass noise (two streams)
};

/// The sector (0..15) that holds a bearing in degrees (any value; wrapped).
int range_sector(double bearing_deg);

/// The 16 exact ranges seen from `tool` (0: nothing in range), before any error.
std::array<double, kRangeSectors> true_ranges(const World& world, const Pose2& tool, double range_mm);

/// One frame: 1 x 16 CV_32FC1. With `noise` and settings.relative_error > 0 each non-zero sector
/// draws one relative error from it, in sector order. Throws std::invalid_argument for a bad setting.
cv::Mat range_ring_frame(const World& world, const Pose2& tool, const RangeRingSettings& settings,
                         Random* noise = nullptr);

/// The sensor of one journey: frames at a pose, and the compass, each with its own noise stream.
class RangeRingSensor {
 public:
  /// Keeps a copy of the marbles. Throws std::invalid_argument for a bad setting.
  RangeRingSensor(World world, const RangeRingSettings& settings);
  [[nodiscard]] cv::Mat frame(const Pose2& tool);
  /// The tool's heading, degrees counter-clockwise from the world's +x axis, in [0, 360), with error.
  [[nodiscard]] double compass_deg(const Pose2& tool);
  [[nodiscard]] const RangeRingSettings& settings() const { return settings_; }

 private:
  World world_;
  RangeRingSettings settings_;
  Random range_noise_;
  Random compass_noise_;
};

/// The sensor as the engine's frame source, rendered at whatever pose `where` gives each time a
/// frame is taken. `sensor` must outlive the source.
std::unique_ptr<pipeline::io::FrameSource> range_ring_camera_source(RangeRingSensor& sensor,
                                                                    std::function<Pose2()> where);

}  // namespace neopipe::sim
