#include "apps/nx_plot.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "apps/cli_support.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {

void write_nx_plot(const std::string& path, const sim::World& world, const rig::NxExploration& e,
                   const rig::VoronoiGraph* truth, const std::vector<Eigen::Vector2d>& track) {
  if (std::filesystem::path(path).extension() != ".png") {
    throw UsageError{fmt::format("--plot {}: the NX plot is a .png", path)};
  }
  constexpr double kScale = 2;     // px per mm
  constexpr double kMargin = 100;  // mm around the world
  const cv::Size size(static_cast<int>((world.size.x() + 2 * kMargin) * kScale),
                      static_cast<int>((world.size.y() + 2 * kMargin) * kScale));
  cv::Mat img(size, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() + kMargin) * kScale)),
                     static_cast<int>(std::lround((world.size.y() + kMargin - p.y()) * kScale)));
  };
  cv::rectangle(img, px({0, 0}), px(world.size), cv::Scalar(180, 180, 180), 1);
  if (truth != nullptr) {
    for (const auto& [a, b] : truth->edges) {
      cv::line(img, px(truth->vertices[a]), px(truth->vertices[b]), cv::Scalar(200, 200, 200), 1, cv::LINE_AA);
    }
    for (const Eigen::Vector2d& v : truth->vertices) cv::circle(img, px(v), 2, cv::Scalar(170, 170, 170), cv::FILLED);
  }
  for (std::size_t i = 1; i < track.size(); ++i) {
    cv::line(img, px(track[i - 1]), px(track[i]), cv::Scalar(80, 80, 230), 1, cv::LINE_AA);
  }
  for (std::size_t p = 0; p < e.map.size() && p < e.place_truth.size(); ++p) {
    for (const nav::nx::Slot& s : e.map.place(p).slots) {
      if (s.state == nav::nx::SlotState::explored && s.to_place < e.place_truth.size()) {
        cv::line(img, px(e.place_truth[p]), px(e.place_truth[s.to_place]), cv::Scalar(200, 110, 0), 2, cv::LINE_AA);
      }
    }
  }
  for (std::size_t p = 0; p < e.place_truth.size(); ++p) {
    cv::circle(img, px(e.place_truth[p]), 4, cv::Scalar(0, 160, 0), cv::FILLED, cv::LINE_AA);
    cv::putText(img, std::to_string(p), px(e.place_truth[p]) + cv::Point(5, 12), cv::FONT_HERSHEY_SIMPLEX, 0.35,
                cv::Scalar(0, 110, 0), 1, cv::LINE_AA);
  }
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    cv::circle(img, px(world.objects[i]), static_cast<int>(world.marble_diameter * kScale / 2), cv::Scalar(0, 0, 0),
               cv::FILLED, cv::LINE_AA);
  }
  if (!pipeline::media::write_image(path, img)) {
    throw std::runtime_error(fmt::format("--plot {}: cannot write the image", path));
  }
}

}  // namespace neopipe::apps
