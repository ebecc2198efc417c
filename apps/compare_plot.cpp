#include "apps/compare_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "apps/chart_colours.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {
namespace {

const cv::Scalar kRateBar(180, 120, 40);
const cv::Scalar kPathBar(60, 140, 220);

void compare_text(cv::Mat& image, const std::string& s, cv::Point at, int align = 0, double scale = 0.45) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  at.x -= align * size.width / 2;  // 0 left, 1 centred, 2 right
  cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kChartInk, 1, cv::LINE_AA);
}

// One panel of horizontal bars, one row per system, over [lo, hi] on x.
struct Panel {
  cv::Rect box;
  double lo = 0;
  double hi = 1;
  [[nodiscard]] int x(double v) const {
    return box.x + static_cast<int>(std::lround((std::clamp(v, lo, hi) - lo) / (hi - lo) * box.width));
  }
};

void axis(cv::Mat& image, const Panel& p, double step, const std::string& title, const char* format) {
  for (double v = p.lo; v <= p.hi + 1e-9; v += step) {
    cv::line(image, {p.x(v), p.box.y}, {p.x(v), p.box.y + p.box.height}, kChartGrid, 1);
    compare_text(image, fmt::format(fmt::runtime(format), v), {p.x(v), p.box.y + p.box.height + 18}, 1);
  }
  cv::rectangle(image, p.box, kChartInk, 1);
  compare_text(image, title, {p.box.x + p.box.width / 2, p.box.y - 10}, 1, 0.5);
}

}  // namespace

void write_compare_plot(const rig::Comparison& c, const std::string& path) {
  const int rows = std::max<int>(1, static_cast<int>(c.results.size()));
  constexpr int kRow = 46;
  cv::Mat image(110 + rows * kRow, 980, CV_8UC3, cv::Scalar(255, 255, 255));
  double low = 1;
  double longest = 1.5;
  for (const rig::ContenderResult& r : c.results) {
    const rig::Interval ci = rig::wilson_interval(r.summary.reached(), std::max<std::int64_t>(r.summary.run(), 1));
    low = std::min(low, ci.low);
    longest = std::max(longest, r.median_path_ratio);
  }
  // Rates zoom onto the interesting top of the scale, in steps of 10 points (5 near the top).
  const double rate_lo = low > 0.8 ? std::floor(low * 20) / 20 : std::floor(low * 10) / 10;
  const Panel rate{{140, 50, 470, rows * kRow}, rate_lo, 1.0};
  const Panel ratio{{700, 50, 250, rows * kRow}, 1.0, std::ceil(longest * 2) / 2};
  axis(image, rate, rate_lo > 0.8 ? 0.05 : 0.1, "goal reached, 95% interval", "{:.2f}");
  // Ticks at 0.5, 1, 2, 5, ... so that at most six fit.
  double ratio_step = 0.5;
  for (const double step : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0}) {
    ratio_step = step;
    if ((ratio.hi - ratio.lo) / step <= 6) break;
  }
  Panel ratio_panel = ratio;
  ratio_panel.hi = ratio.lo + std::ceil((ratio.hi - ratio.lo) / ratio_step) * ratio_step;
  axis(image, ratio_panel, ratio_step, "median path / straight line", "{:.1f}");
  for (int i = 0; i < static_cast<int>(c.results.size()); ++i) {
    const rig::ContenderResult& r = c.results[static_cast<std::size_t>(i)];
    const std::int64_t n = std::max<std::int64_t>(r.summary.run(), 1);
    const double rate_v = static_cast<double>(r.summary.reached()) / static_cast<double>(n);
    const rig::Interval ci = rig::wilson_interval(r.summary.reached(), n);
    const int y = rate.box.y + i * kRow + kRow / 2;
    compare_text(image, r.system, {rate.box.x - 10, y + 5}, 2, 0.5);
    cv::rectangle(image, {rate.x(rate.lo), y - 12}, {rate.x(rate_v), y + 12}, kRateBar, cv::FILLED);
    cv::line(image, {rate.x(ci.low), y}, {rate.x(ci.high), y}, kChartInk, 2);
    cv::line(image, {rate.x(ci.low), y - 7}, {rate.x(ci.low), y + 7}, kChartInk, 2);
    cv::line(image, {rate.x(ci.high), y - 7}, {rate.x(ci.high), y + 7}, kChartInk, 2);
    compare_text(image, fmt::format("{:.1f}%", 100 * rate_v), {rate.x(rate.lo) + 6, y + 5});
    if (r.median_path_ratio > 0) {
      cv::rectangle(image, {ratio_panel.x(ratio.lo), y - 12}, {ratio_panel.x(r.median_path_ratio), y + 12}, kPathBar,
                    cv::FILLED);
      compare_text(image, fmt::format("{:.2f}", r.median_path_ratio), {ratio_panel.x(ratio.lo) + 6, y + 5});
    }
  }
  compare_text(image, fmt::format("{} journeys per system, the same pairs and arm errors", c.pairs.size()),
               {image.cols / 2, image.rows - 14}, 1);
  if (!pipeline::media::write_image(path, image)) {
    throw std::runtime_error(fmt::format("--plot {}: cannot write the image", path));
  }
}

}  // namespace neopipe::apps
