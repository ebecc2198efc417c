#include "apps/reliability_diagram.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "apps/chart_colours.hpp"
#include "pipeline/media/media.hpp"
#include "rig/outcome.hpp"

namespace neopipe::apps {
namespace {

const cv::Scalar kBlue(180, 90, 20);

void text(cv::Mat& image, const std::string& s, cv::Point at, double scale = 0.45, int align = 0) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  at.x -= align * size.width / 2;  // 0 left, 1 centred, 2 right
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kChartInk, 1, cv::LINE_AA);
}

}  // namespace

std::vector<ForecastBin> forecast_bins(const std::vector<ForecastOutcome>& journeys) {
  constexpr std::array kEdges{0.0, 0.8, 0.9, 0.97, 1.0};
  std::vector<ForecastBin> bins;
  for (std::size_t b = 0; b + 1 < kEdges.size(); ++b) {
    ForecastBin bin;
    bin.low = kEdges[b];
    bin.high = kEdges[b + 1];
    const bool last = b + 2 == kEdges.size();
    for (const ForecastOutcome& j : journeys) {
      if (j.forecast < bin.low || (j.forecast >= bin.high && !last)) continue;
      ++bin.journeys;
      bin.reached += j.reached ? 1 : 0;
      bin.mean_forecast += j.forecast;
    }
    if (bin.journeys > 0) {
      bin.mean_forecast /= bin.journeys;
      const rig::Interval w = rig::wilson_interval(bin.reached, bin.journeys);
      bin.ci_low = w.low;
      bin.ci_high = w.high;
    }
    bins.push_back(bin);
  }
  return bins;
}

void write_reliability_diagram(const std::vector<ForecastOutcome>& journeys, const std::string& title,
                               const std::string& path) {
  const std::vector<ForecastBin> bins = forecast_bins(journeys);
  cv::Mat image(700, 760, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect plot(90, 60, 600, 520);
  // The axes span forecasts from 0.5: below it journeys are few and the diagram's interest is near 1.
  constexpr double kLow = 0.5;
  const auto px = [&](double x, double y) {
    return cv::Point(plot.x + static_cast<int>(std::lround((x - kLow) / (1 - kLow) * plot.width)),
                     plot.y + plot.height - static_cast<int>(std::lround((y - kLow) / (1 - kLow) * plot.height)));
  };
  const auto clamp = [&](double v) { return std::clamp(v, kLow, 1.0); };
  for (int k = 0; k <= 10; ++k) {
    const double v = kLow + k * (1 - kLow) / 10;
    cv::line(image, px(v, kLow), px(v, 1), kChartGrid, 1);
    cv::line(image, px(kLow, v), px(1, v), kChartGrid, 1);
    text(image, fmt::format("{:.2f}", v), px(v, kLow) + cv::Point(0, 22), 0.42, 1);
    text(image, fmt::format("{:.2f}", v), px(kLow, v) + cv::Point(-8, 5), 0.42, 2);
  }
  cv::rectangle(image, plot, kChartInk, 1);
  cv::line(image, px(kLow, kLow), px(1, 1), kChartInk, 1, cv::LINE_AA);
  text(image, title, {plot.x + plot.width / 2, 24}, 0.55, 1);
  text(image, "planned reliability R (mean of the bin)", {plot.x + plot.width / 2, plot.y + plot.height + 50}, 0.5, 1);
  text(image, "share that reached the goal, 95% CI", {plot.x - 70, plot.y - 12}, 0.45, 0);
  int line = 0;
  for (const ForecastBin& b : bins) {
    const std::string label =
        fmt::format("R in [{:.2f}, {:.2f}{}: {} journeys", b.low, b.high, b.high >= 1 ? "]" : ")", b.journeys);
    if (b.journeys == 0) {
      text(image, label, {plot.x + 15, plot.y + 25 + 20 * line++}, 0.42);
      continue;
    }
    const double x = b.mean_forecast;
    cv::line(image, px(x, clamp(b.ci_low)), px(x, clamp(b.ci_high)), kBlue, 2, cv::LINE_AA);
    for (const double y : {b.ci_low, b.ci_high})
      cv::line(image, px(x, clamp(y)) - cv::Point(6, 0), px(x, clamp(y)) + cv::Point(6, 0), kBlue, 2);
    cv::circle(image, px(x, clamp(static_cast<double>(b.reached) / b.journeys)), 6, kBlue, cv::FILLED, cv::LINE_AA);
    text(image, fmt::format("{}, {:.1f}% reached", label, 100.0 * b.reached / b.journeys),
         {plot.x + 15, plot.y + 25 + 20 * line++}, 0.42);
  }
  if (!pipeline::media::write_image(path, image)) {
    throw std::runtime_error(fmt::format("--reliability-diagram {}: cannot write the image", path));
  }
}

}  // namespace neopipe::apps
