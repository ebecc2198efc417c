#pragma once
// `neopipe nav --video`: the onboard view as the navigator saw it, each blob it found circled and
// the landmark it holds marked, one video frame per camera frame.

#include <memory>
#include <optional>
#include <string>

#include "nav/navigator/navigator.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {

class NavVideo final : public nav::navigator::Observer {
 public:
  /// Throws std::runtime_error naming `path` unless it is a .mp4, .avi or .mkv file that can be written.
  NavVideo(std::string path, double window_side, int side_px);
  void landmark_held(std::size_t entry, const Eigen::Vector2d& window_position) override;
  void frame_seen(const pipeline::io::SourceFrame& frame, const nav::navigator::Sighting& sighting) override;
  /// Finishes the file; throws when nothing was written to it.
  void close();

 private:
  cv::Point to_pixel(const Eigen::Vector2d& window_position) const;

  std::string path_;
  double side_;
  int side_px_;
  std::unique_ptr<pipeline::media::VideoWriter> writer_;
  std::optional<Eigen::Vector2d> held_;  ///< the last landmark held, drawn until the next move shows
  std::size_t entry_ = 0;
  std::int64_t frames_ = 0;
};

}  // namespace neopipe::apps
