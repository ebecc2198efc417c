#include "sim/marble_truth.hpp"

namespace neopipe::sim {

std::vector<MarbleTruth> marble_truth(std::span<const Eigen::Vector2d> centres, double diameter,
                                      const PinholeCamera& camera, MarbleShape shape) {
  const double height = shape == MarbleShape::sphere ? diameter / 2 : 0.0;
  const cv::Size s = camera.size();
  std::vector<MarbleTruth> out;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const auto c = camera.project({centres[i].x(), centres[i].y(), height});
    const auto c0 = camera.project({centres[i].x(), centres[i].y(), 0});
    if (c && c0 && c->x() > -0.5 && c->y() > -0.5 && c->x() < s.width - 0.5 && c->y() < s.height - 0.5) {
      out.push_back({static_cast<int>(i), c->x(), c->y(), c0->x(), c0->y()});
    }
  }
  return out;
}

}  // namespace neopipe::sim
