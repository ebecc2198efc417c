#pragma once
// The panoramic sensor the tool carries for the navigators of qrm.md and qualnav.md (qualnav.md §2):
// a 360° ring image in which every marble within R_s is a flat disc labelled with its identity,
// and a compass. The robot is the tool point; the sensor sees from there.
//
// The ring image is 3600 x 320, CV_16SC1. Column u looks at bearing (u + 1/2) * 0.1°,
// counter-clockwise from the tool's +x axis; rows are 0.1° apart too, so a disc of angular radius ρ
// is a circle of ρ / 0.1° pixels on the image (both axes 0.1° per pixel), centred on row 160
// (pixel centres: row 160's centre, not the image's half height 159.5). A marble of radius r_m whose
// centre lies d from the tool has ρ = asin(r_m / d). A pixel belongs to a disc when its centre lies
// within that circle (no anti-aliasing); discs wrap across columns 0 / 3599 and are cut by the top
// and bottom rows. Its value is id + 1 (background 0), so worlds of up to 32,767 marbles keep every
// identity; nearer discs are drawn last and cover farther ones. A marble whose centre is closer
// than r_m (the tool inside it) has no angular radius: it is not drawn, and reported.
//
// Noise: each disc's bearing may be jittered by a seeded Gaussian (the spec's "configured noise",
// 0 by default); the compass reads the tool's heading with a seeded Gaussian error (σ = 1°).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/io/frame_source.hpp"
#include "sim/pose2.hpp"
#include "sim/random.hpp"
#include "sim/world.hpp"

namespace neopipe::sim {

inline constexpr int kRingWidth = 3600;
inline constexpr int kRingHeight = 320;
inline constexpr double kRingDegreesPerPixel = 0.1;
/// The row discs are centred on (its pixel centre).
inline constexpr int kRingMiddleRow = 160;
/// Values are id + 1 in a signed 16-bit pixel.
inline constexpr std::size_t kRingMaxMarbles = 32767;
/// The robot keeps at least this far (mm) from every marble's surface (qualnav.md §2).
inline constexpr double kMinClearanceMm = 10;

struct PanoramaSettings {
  double range_mm = 600;         ///< R_s: a marble is seen when its centre lies within it
  double bearing_noise_deg = 0;  ///< sd of the Gaussian jitter of each disc's bearing
  double compass_sigma_deg = 1;  ///< sd of the compass's error
  std::uint64_t seed = 1;        ///< the bearing and compass noise (two streams)
};

/// The image column coordinate (pixel centres at integers) of a bearing in degrees, and back (the
/// bearing wrapped to [0, 360)).
double ring_column(double bearing_deg);
double ring_bearing_deg(double column);

/// A marble as the sensor would see it from a pose, without noise or occlusion: the truth.
struct MarbleInView {
  std::uint32_t id = 0;
  double bearing_deg = 0;  ///< [0, 360), counter-clockwise from the tool's +x axis
  double distance_mm = 0;  ///< tool to marble centre
  double angular_radius_deg = 0;
};

/// The marbles within `range_mm` of the tool and outside it (distance > radius), in id order.
std::vector<MarbleInView> marbles_in_view(const World& world, const Pose2& tool, double range_mm);

struct Ring {
  cv::Mat image;  ///< kRingHeight x kRingWidth, CV_16SC1
  int discs = 0;  ///< discs drawn (some may be hidden entirely)
  /// Marbles whose centre lies within their radius of the tool: the tool is inside them, nothing is
  /// drawn for them (the robot keeps kMinClearanceMm from marbles, so a rig never asks for this).
  std::vector<std::uint32_t> inside;
};

/// Draws the ring seen from `tool`. With `noise` and settings.bearing_noise_deg > 0 each marble in
/// view (in id order) draws one Gaussian jitter of its bearing from it. Throws std::invalid_argument
/// for a world of more than kRingMaxMarbles marbles or a negative setting.
Ring render_ring(const World& world, const Pose2& tool, const PanoramaSettings& settings, Random* noise = nullptr);

/// The marble surface nearest a point: which marble and how far (negative inside it).
struct NearestSurface {
  std::uint32_t id = 0;
  double gap_mm = 0;
};
/// nullopt for a world without marbles.
std::optional<NearestSurface> nearest_surface(const World& world, const Eigen::Vector2d& point);
/// Whether the tool at `point` keeps at least `min_gap_mm` from every marble's surface.
bool keeps_clear(const World& world, const Eigen::Vector2d& point, double min_gap_mm = kMinClearanceMm);

/// The sensor of one journey: the ring at a pose, and the compass, each with its own noise stream.
class PanoramicSensor {
 public:
  /// Keeps a copy of the marbles. Throws std::invalid_argument as render_ring does.
  PanoramicSensor(World world, const PanoramaSettings& settings);
  [[nodiscard]] Ring ring(const Pose2& tool);
  /// The tool's heading, degrees counter-clockwise from the world's +x axis in [0, 360), with a
  /// Gaussian error of settings.compass_sigma_deg.
  [[nodiscard]] double compass_deg(const Pose2& tool);
  [[nodiscard]] const PanoramaSettings& settings() const { return settings_; }

 private:
  World world_;
  PanoramaSettings settings_;
  Random ring_noise_;
  Random compass_noise_;
};

/// The sensor's ring as the engine's frame source: CV_16SC1 frames (the panorama graph's s16
/// source), rendered at whatever pose `where` gives each time a frame is taken. `sensor` must
/// outlive the source.
std::unique_ptr<pipeline::io::FrameSource> panoramic_camera_source(PanoramicSensor& sensor,
                                                                   std::function<Pose2()> where);

}  // namespace neopipe::sim
