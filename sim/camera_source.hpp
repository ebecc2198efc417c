#pragma once
// Simulated cameras as the engine's frame source: the navigator runs the same graph on these
// frames as `neopipe run` does on files. A source renders frame i when asked for it; what the
// camera looks at comes from a callback, so the navigator's source can follow the arm without
// seeing where the arm is.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/io/frame_source.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/rendering.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace neopipe::sim {

/// What a frame shows: the marbles (mm) and the camera, for frame `index`; nothing ends the stream.
/// An interlaced camera (Rendering::interlace) takes its odd rows half a frame later: where the
/// marbles and the camera are then, if they moved (else the frame's own).
struct Shot {
  std::vector<Eigen::Vector2d> marbles;
  PinholeCamera camera;
  std::optional<std::vector<Eigen::Vector2d>> odd_marbles = std::nullopt;
  std::optional<PinholeCamera> odd_camera = std::nullopt;
};
using ShotProvider = std::function<std::optional<Shot>(std::int64_t index)>;

class SimCameraSource final : public pipeline::io::FrameSource {
 public:
  SimCameraSource(std::string description, const ImageModel& model, cv::Size size, double marble_diameter,
                  ShotProvider shots, pipeline::io::ColorFormat format, std::optional<std::int64_t> frames,
                  double fps = 30);
  /// Rendering with `rendering` (SceneRenderer) for cameras with `camera`'s intrinsics and lens.
  SimCameraSource(std::string description, const Rendering& rendering, const PinholeCamera& camera,
                  double marble_diameter, ShotProvider shots, pipeline::io::ColorFormat format,
                  std::optional<std::int64_t> frames, double fps = 30);
  std::optional<pipeline::io::SourceFrame> next() override;
  [[nodiscard]] std::string description() const override { return description_; }
  [[nodiscard]] double fps() const override { return fps_; }
  [[nodiscard]] std::optional<std::int64_t> frame_count() const override { return frames_; }

 private:
  std::string description_;
  std::optional<MarbleRenderer> renderer_;  // ImageModel
  std::optional<SceneRenderer> realistic_;  // Rendering
  double diameter_;
  ShotProvider shots_;
  pipeline::io::ColorFormat format_;
  std::optional<std::int64_t> frames_;
  double fps_;
  std::int64_t index_ = 0;
};

/// The onboard camera over `world` at whatever pose `where` gives each time a frame is taken.
std::unique_ptr<SimCameraSource> onboard_camera_source(const World& world, const OnboardCameraConfig& camera,
                                                       const ImageModel& model, std::function<Pose2()> where,
                                                       pipeline::io::ColorFormat format);

/// The same with `rendering` (presets: rendering_for in sim/realism.hpp) and its lens; `camera`'s
/// window_plane_z as given (onboard_config_for puts it at the marbles' centres for spheres).
std::unique_ptr<SimCameraSource> onboard_camera_source(const World& world, const OnboardCameraConfig& camera,
                                                       const Rendering& rendering, std::function<Pose2()> where,
                                                       pipeline::io::ColorFormat format);

/// The onboard camera over `world` along `path`, one frame per pose.
std::unique_ptr<SimCameraSource> onboard_path_source(const World& world, const OnboardCameraConfig& camera,
                                                     const ImageModel& model, std::vector<Pose2> path,
                                                     pipeline::io::ColorFormat format);
/// The same with `rendering`; interlaced frames take their odd rows halfway to the next pose.
std::unique_ptr<SimCameraSource> onboard_path_source(const World& world, const OnboardCameraConfig& camera,
                                                     const Rendering& rendering, std::vector<Pose2> path,
                                                     pipeline::io::ColorFormat format);

}  // namespace neopipe::sim
