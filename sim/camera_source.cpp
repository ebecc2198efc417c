#include "sim/camera_source.hpp"

#include <opencv2/imgproc.hpp>

namespace neopipe::sim {

SimCameraSource::SimCameraSource(std::string description, const ImageModel& model, cv::Size size,
                                 double marble_diameter, ShotProvider shots, pipeline::io::ColorFormat format,
                                 std::optional<std::int64_t> frames, double fps)
    : description_(std::move(description)),
      renderer_(std::in_place, model, size),
      diameter_(marble_diameter),
      shots_(std::move(shots)),
      format_(format),
      frames_(frames),
      fps_(fps) {}

SimCameraSource::SimCameraSource(std::string description, const Rendering& rendering, const PinholeCamera& camera,
                                 double marble_diameter, ShotProvider shots, pipeline::io::ColorFormat format,
                                 std::optional<std::int64_t> frames, double fps)
    : description_(std::move(description)),
      realistic_(std::in_place, rendering, camera),
      diameter_(marble_diameter),
      shots_(std::move(shots)),
      format_(format),
      frames_(frames),
      fps_(fps) {}

std::optional<pipeline::io::SourceFrame> SimCameraSource::next() {
  if (frames_ && index_ >= *frames_) return std::nullopt;
  const auto shot = shots_(index_);
  if (!shot) return std::nullopt;
  pipeline::io::SourceFrame f;
  f.index = index_;
  if (realistic_) {
    f.image = realistic_->render(shot->marbles, shot->camera, shot->odd_marbles ? *shot->odd_marbles : shot->marbles,
                                 shot->odd_camera ? *shot->odd_camera : shot->camera, diameter_, index_);
  } else {
    f.image = renderer_->render(shot->marbles, diameter_, shot->camera, index_);
  }
  if (format_ == pipeline::io::ColorFormat::bgr) cv::cvtColor(f.image, f.image, cv::COLOR_GRAY2BGR);
  ++index_;
  return f;
}

std::unique_ptr<SimCameraSource> onboard_camera_source(const World& world, const OnboardCameraConfig& camera,
                                                       const ImageModel& model, std::function<Pose2()> where,
                                                       pipeline::io::ColorFormat format) {
  auto shots = [objects = world.objects, camera, where = std::move(where)](std::int64_t) -> std::optional<Shot> {
    return Shot{objects, make_onboard_camera(where(), camera)};
  };
  return std::make_unique<SimCameraSource>("onboard camera", model, cv::Size(camera.side_px, camera.side_px),
                                           world.marble_diameter, std::move(shots), format, std::nullopt);
}

std::unique_ptr<SimCameraSource> onboard_path_source(const World& world, const OnboardCameraConfig& camera,
                                                     const ImageModel& model, std::vector<Pose2> path,
                                                     pipeline::io::ColorFormat format) {
  const auto n = static_cast<std::int64_t>(path.size());
  auto shots = [objects = world.objects, camera, path = std::move(path)](std::int64_t i) -> std::optional<Shot> {
    return Shot{objects, make_onboard_camera(path[static_cast<std::size_t>(i)], camera)};
  };
  return std::make_unique<SimCameraSource>("onboard camera along a path", model,
                                           cv::Size(camera.side_px, camera.side_px), world.marble_diameter,
                                           std::move(shots), format, n);
}

}  // namespace neopipe::sim

namespace neopipe::sim {

std::unique_ptr<SimCameraSource> onboard_camera_source(const World& world, const OnboardCameraConfig& camera,
                                                       const Rendering& rendering, std::function<Pose2()> where,
                                                       pipeline::io::ColorFormat format) {
  // The arm stands still while a frame is taken: both fields of an interlaced frame see one pose.
  const Intrinsics k = onboard_intrinsics(camera, rendering);
  auto shots = [objects = world.objects, camera, k, where = std::move(where)](std::int64_t) -> std::optional<Shot> {
    return Shot{objects, onboard_camera_at(where(), camera, k)};
  };
  return std::make_unique<SimCameraSource>("onboard camera", rendering, onboard_camera_at({}, camera, k),
                                           world.marble_diameter, std::move(shots), format, std::nullopt);
}

std::unique_ptr<SimCameraSource> onboard_path_source(const World& world, const OnboardCameraConfig& camera,
                                                     const Rendering& rendering, std::vector<Pose2> path,
                                                     pipeline::io::ColorFormat format) {
  const auto n = static_cast<std::int64_t>(path.size());
  const Intrinsics k = onboard_intrinsics(camera, rendering);
  auto shots = [objects = world.objects, camera, k, interlace = rendering.interlace,
                path = std::move(path)](std::int64_t i) -> std::optional<Shot> {
    const auto at = static_cast<std::size_t>(i);
    Shot shot{objects, onboard_camera_at(path[at], camera, k)};
    if (interlace && at + 1 < path.size()) {
      const Pose2& a = path[at];
      const Pose2& b = path[at + 1];
      shot.odd_camera = onboard_camera_at({(a.x + b.x) / 2, (a.y + b.y) / 2, (a.theta + b.theta) / 2}, camera, k);
    }
    return shot;
  };
  return std::make_unique<SimCameraSource>("onboard camera along a path", rendering, onboard_camera_at({}, camera, k),
                                           world.marble_diameter, std::move(shots), format, n);
}

}  // namespace neopipe::sim
