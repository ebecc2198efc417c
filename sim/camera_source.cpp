#include "sim/camera_source.hpp"

#include <opencv2/imgproc.hpp>

namespace neopipe::sim {

SimCameraSource::SimCameraSource(std::string description, const ImageModel& model, cv::Size size,
                                 double marble_diameter, ShotProvider shots, pipeline::io::ColorFormat format,
                                 std::optional<std::int64_t> frames, double fps)
    : description_(std::move(description)),
      renderer_(model, size),
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
  f.image = renderer_.render(shot->marbles, diameter_, shot->camera, index_);
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
