#include "apps/qrm_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "apps/chart_colours.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {
namespace {

// BGR.
const cv::Scalar kTrueEdge(200, 200, 200);
const cv::Scalar kCertainEdge(180, 119, 31);    // blue: c_ij = 0
const cv::Scalar kUncertainEdge(14, 127, 255);  // orange: a candidate not yet certain
const cv::Scalar kWrongEdge(40, 39, 214);       // red: a certain edge the truth lacks
const cv::Scalar kImaging(44, 160, 44);

}  // namespace

void write_qrm_build_plot(const sim::World& world, const rig::QrmBuildResult& result, const std::string& path) {
  if (result.steps.empty()) throw std::runtime_error(fmt::format("--plot {}: no image was taken", path));
  constexpr int kSide = 900;
  constexpr int kPad = 40;
  constexpr int kFooter = 70;
  const double scale = (kSide - 2.0 * kPad) / std::max(world.size.x(), world.size.y());
  cv::Mat image(kSide + kFooter, kSide, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround(kPad + p.x() * scale)),
                     static_cast<int>(std::lround(kPad + (world.size.y() - p.y()) * scale)));
  };
  cv::rectangle(image, px({0, world.size.y()}), px({world.size.x(), 0}), kChartGrid, 1);
  const rig::QrmMetrics& m = result.steps.back().metrics;
  for (const auto& [i, j] : result.true_rng) {
    cv::line(image, px(world.objects[i]), px(world.objects[j]), kTrueEdge, 7, cv::LINE_AA);
  }
  for (const auto& [i, j] : m.rng) {
    const bool certain = std::binary_search(m.certain_rng.begin(), m.certain_rng.end(), std::pair{i, j});
    const bool true_edge = std::binary_search(result.true_rng.begin(), result.true_rng.end(), std::pair{i, j});
    const cv::Scalar colour = !certain ? kUncertainEdge : true_edge ? kCertainEdge : kWrongEdge;
    cv::line(image, px(world.objects[i]), px(world.objects[j]), colour, certain ? 2 : 1, cv::LINE_AA);
  }
  for (const Eigen::Vector2d& p : result.positions) {
    const cv::Point c = px(p);
    cv::drawMarker(image, c, kImaging, cv::MARKER_CROSS, 8, 1, cv::LINE_AA);
  }
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const cv::Point c = px(world.objects[i]);
    cv::circle(image, c, 4, kChartInk, cv::FILLED, cv::LINE_AA);
    cv::putText(image, std::to_string(i), c + cv::Point(5, -5), cv::FONT_HERSHEY_SIMPLEX, 0.4, kChartInk, 1,
                cv::LINE_AA);
  }
  const std::string line1 = fmt::format(
      "{} images, k = {}: M1 {:.1f}%  M2 {:.1f}%  M3 {:.3f}  M4 {:.1f}%; RNG: {} true, {} candidates, {} certain",
      result.steps.size(), result.steps.back().image.fused.landmarks, m.m1, m.m2, m.m3, m.m4, result.true_rng.size(),
      m.rng.size(), m.certain_rng.size());
  const std::string line2 =
      "grey: true RNG; blue: certain estimated edge (c = 0); orange: candidate (c > 0); red: certain but false; "
      "green +: imaging";
  cv::putText(image, line1, {kPad, kSide + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kChartInk, 1, cv::LINE_AA);
  cv::putText(image, line2, {kPad, kSide + 45}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kChartInk, 1, cv::LINE_AA);
  if (!pipeline::media::write_image(path, image)) {
    throw std::runtime_error(fmt::format("--plot {}: cannot write the PNG", path));
  }
}

}  // namespace neopipe::apps
