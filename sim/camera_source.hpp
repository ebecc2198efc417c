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
#include "sim/world.hpp"

namespace neopipe::sim {

/// What a frame shows: the marbles (mm) and the camera, for frame `index`; nothing ends the stream.
struct Shot {
  std::vector<Eigen::Vector2d> marbles;
  PinholeCamera camera;
};
using ShotProvider = std::function<std::optional<Shot>(std::int64_t index)>;

class SimCameraSource final : public pipeline::io::FrameSource {
 public:
  SimCameraSource(std::string description, const ImageModel& model, cv::Size size, double marble_diameter,
                  ShotProvider shots, pipeline::io::ColorFormat format, std::optional<std::int64_t> frames,
                  double fps = 30);
  std::optional<pipeline::io::SourceFrame> next() override;
  [[nodiscard]] std::string description() const override { return description_; }
  [[nodiscard]] double fps() const override { return fps_; }
  [[nodiscard]] std::optional<std::int64_t> frame_count() const override { return frames_; }

 private:
  std::string description_;
  MarbleRenderer renderer_;
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

/// The onboard camera over `world` along `path`, one frame per pose.
std::unique_ptr<SimCameraSource> onboard_path_source(const World& world, const OnboardCameraConfig& camera,
                                                     const ImageModel& model, std::vector<Pose2> path,
                                                     pipeline::io::ColorFormat format);

}  // namespace neopipe::sim
