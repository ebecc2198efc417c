#include "apps/map_stats_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "apps/chart_colours.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::apps {
namespace {

namespace mm = nav::mapmaker;

// Field indices into StatisticsRow::counts (the order of mm::count_names()).
constexpr std::size_t kGeneral = 0;
constexpr std::size_t kObvious = 3;
constexpr std::size_t kIsolated = 4;
constexpr std::size_t kWithTrajectories = 5;
constexpr std::size_t kNewParkways = 9;

// Matplotlib's tab10, BGR: distinct for up to ten curves.
cv::Scalar palette(std::size_t i) {
  static const std::array<cv::Scalar, 10> colours{
      cv::Scalar(180, 119, 31),  cv::Scalar(14, 127, 255), cv::Scalar(44, 160, 44),   cv::Scalar(40, 39, 214),
      cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140),  cv::Scalar(194, 119, 227), cv::Scalar(127, 127, 127),
      cv::Scalar(34, 189, 188),  cv::Scalar(207, 190, 23)};
  return colours[i % colours.size()];
}

struct Point {
  double x, y, lo, hi;
};

struct Series {
  std::string label;
  cv::Scalar colour;
  bool dashed = false;
  bool bars = true;  // draw the CI
  std::vector<Point> points;
};

// A "nice" tick spacing (1, 2 or 5 times a power of ten) giving about `count` ticks over `span`.
double tick_step(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10 * power;
}

class Panel {
 public:
  Panel(cv::Mat& image, cv::Rect area, std::string title, std::string x_label, std::string y_label)
      : image_(image),
        plot_(area.x + 70, area.y + 40, area.width - 90, area.height - 95),
        title_(std::move(title)),
        x_label_(std::move(x_label)),
        y_label_(std::move(y_label)) {}

  void draw(const std::vector<Series>& series) {
    double x_max = 1;
    double y_max = 1;
    for (const Series& s : series) {
      for (const Point& p : s.points) {
        x_max = std::max(x_max, p.x);
        y_max = std::max({y_max, p.y, p.hi});
      }
    }
    const double xs = tick_step(x_max, 8);
    const double ys = tick_step(y_max, 6);
    x_max_ = std::ceil(x_max / xs) * xs;
    y_max_ = std::ceil(y_max / ys) * ys;
    axes(xs, ys);
    for (const Series& s : series) curve(s);
    legend(series);
  }

 private:
  cv::Point px(double x, double y) const {
    return {plot_.x + static_cast<int>(std::lround(x / x_max_ * plot_.width)),
            plot_.y + plot_.height - static_cast<int>(std::lround(y / y_max_ * plot_.height))};
  }

  void text(const std::string& s, cv::Point at, double scale = 0.45, int align = 0) {
    int baseline = 0;
    const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    // align: 0 left, 1 centred, 2 right
    at.x -= align * size.width / 2;
    cv::putText(image_, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kChartInk, 1, cv::LINE_AA);
  }

  void axes(double xs, double ys) {
    for (double x = 0; x <= x_max_ + 1e-9; x += xs) {
      cv::line(image_, px(x, 0), px(x, y_max_), kChartGrid, 1);
      cv::line(image_, px(x, 0), px(x, 0) + cv::Point(0, 5), kChartInk, 1);
      text(fmt::format("{:g}", x), px(x, 0) + cv::Point(0, 22), 0.42, 1);
    }
    for (double y = 0; y <= y_max_ + 1e-9; y += ys) {
      cv::line(image_, px(0, y), px(x_max_, y), kChartGrid, 1);
      cv::line(image_, px(0, y), px(0, y) - cv::Point(5, 0), kChartInk, 1);
      text(fmt::format("{:g}", y), px(0, y) + cv::Point(-9, 5), 0.42, 2);
    }
    cv::rectangle(image_, plot_, kChartInk, 1);
    text(title_, {plot_.x + plot_.width / 2, plot_.y - 14}, 0.55, 1);
    text(x_label_, {plot_.x + plot_.width / 2, plot_.y + plot_.height + 45}, 0.5, 1);
    // A vertical label would need rotated text; above the axis reads as well.
    text(y_label_, {plot_.x - 60, plot_.y - 14}, 0.45, 0);
  }

  void segment(cv::Point a, cv::Point b, const cv::Scalar& colour, bool dashed) {
    if (!dashed) {
      cv::line(image_, a, b, colour, 2, cv::LINE_AA);
      return;
    }
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    constexpr double kDash = 7;
    for (double t = 0; t < length; t += 2 * kDash) {
      const double u = std::min(t + kDash, length);
      const auto at = [&](double s) {
        return cv::Point(static_cast<int>(std::lround(a.x + (b.x - a.x) * s / length)),
                         static_cast<int>(std::lround(a.y + (b.y - a.y) * s / length)));
      };
      cv::line(image_, at(t), at(u), colour, 2, cv::LINE_AA);
    }
  }

  void curve(const Series& s) {
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i) {
      segment(px(s.points[i].x, s.points[i].y), px(s.points[i + 1].x, s.points[i + 1].y), s.colour, s.dashed);
    }
    if (!s.bars) return;
    for (const Point& p : s.points) {
      const cv::Point lo = px(p.x, std::max(0.0, p.lo));
      const cv::Point hi = px(p.x, p.hi);
      cv::line(image_, lo, hi, s.colour, 1, cv::LINE_AA);
      cv::line(image_, lo - cv::Point(3, 0), lo + cv::Point(3, 0), s.colour, 1);
      cv::line(image_, hi - cv::Point(3, 0), hi + cv::Point(3, 0), s.colour, 1);
    }
  }

  // Series without a label stay out of the legend (one key for all the dashed Poisson curves).
  void legend(const std::vector<Series>& all) {
    std::vector<const Series*> series;
    for (const Series& s : all) {
      if (!s.label.empty()) series.push_back(&s);
    }
    const int row = 18;
    int width = 0;
    for (const Series* s : series) {
      int baseline = 0;
      width = std::max(width, cv::getTextSize(s->label, cv::FONT_HERSHEY_SIMPLEX, 0.42, 1, &baseline).width);
    }
    // Top left: counts grow with population, so that corner stays clear.
    const cv::Rect box(plot_.x + 8, plot_.y + 6, width + 44, row * static_cast<int>(series.size()) + 8);
    cv::rectangle(image_, box, cv::Scalar(255, 255, 255), cv::FILLED);
    cv::rectangle(image_, box, kChartGrid, 1);
    for (std::size_t i = 0; i < series.size(); ++i) {
      const int y = box.y + 14 + row * static_cast<int>(i);
      segment({box.x + 6, y - 4}, {box.x + 32, y - 4}, series[i]->colour, series[i]->dashed);
      text(series[i]->label, {box.x + 38, y}, 0.42);
    }
  }

  cv::Mat& image_;
  cv::Rect plot_;
  std::string title_, x_label_, y_label_;
  double x_max_ = 1;
  double y_max_ = 1;
};

Series series_of(const std::vector<mm::StatisticsRow>& rows, double window, std::size_t field, std::string label,
                 const cv::Scalar& colour) {
  Series s{std::move(label), colour, false, true, {}};
  for (const mm::StatisticsRow& r : rows) {
    if (r.window.side != window) continue;
    const mm::Summary& c = r.counts[field];
    s.points.push_back({static_cast<double>(r.population), c.mean, c.ci_low, c.ci_high});
  }
  return s;
}

Series poisson_of(const std::vector<mm::StatisticsRow>& rows, double window, std::string label,
                  const cv::Scalar& colour) {
  Series s{std::move(label), colour, true, false, {}};
  for (const mm::StatisticsRow& r : rows) {
    if (r.window.side != window) continue;
    s.points.push_back({static_cast<double>(r.population), r.poisson_new_parkways, 0, 0});
  }
  return s;
}

}  // namespace

void write_map_stats_plot(const std::vector<mm::StatisticsRow>& rows, const std::string& path) {
  std::vector<double> windows;
  for (const mm::StatisticsRow& r : rows) {
    if (std::find(windows.begin(), windows.end(), r.window.side) == windows.end()) windows.push_back(r.window.side);
  }
  if (windows.empty()) throw std::runtime_error(fmt::format("--plot {}: nothing to plot", path));
  // The lower panels show one window, as the paper's do: the one nearest its 5 x 5.
  const double reference = *std::min_element(windows.begin(), windows.end(),
                                             [](double a, double b) { return std::abs(a - 5) < std::abs(b - 5); });
  const std::string ref = fmt::format("{:g}x{:g}", reference, reference);

  cv::Mat image(1100, 1400, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<Series> top;
  for (std::size_t i = 0; i < windows.size(); ++i) {
    top.push_back(series_of(rows, windows[i], kGeneral, fmt::format("{:g}x{:g}", windows[i], windows[i]), palette(i)));
  }
  for (std::size_t i = 0; i < windows.size(); ++i) {
    top.push_back(poisson_of(rows, windows[i], i == 0 ? "dashed: Poisson, parkways founded" : "", palette(i)));
  }
  Panel(image, {0, 0, 1400, 550}, "Fig. 7: general parkways vs population (95% CI); dashed: Poisson estimate",
        "population (objects)", "parkways")
      .draw(top);

  Panel(image, {0, 550, 700, 550}, fmt::format("Fig. 7: parkways of each kind, window {}", ref), "population (objects)",
        "parkways")
      .draw({series_of(rows, reference, kObvious, "obvious", palette(3)),
             series_of(rows, reference, kIsolated, "isolated", palette(1)),
             series_of(rows, reference, kGeneral, "general", palette(0)),
             series_of(rows, reference, kNewParkways, "founded (simulated)", palette(7)),
             poisson_of(rows, reference, "founded (Poisson)", palette(7))});
  Panel(image, {700, 550, 700, 550}, fmt::format("Fig. 11: strongly connected components, window {}", ref),
        "population (objects)", "components")
      .draw({series_of(rows, reference, kIsolated, "parkways only", palette(3)),
             series_of(rows, reference, kWithTrajectories, "with trajectories", palette(2))});
  if (!pipeline::media::write_image(path, image))
    throw std::runtime_error(fmt::format("--plot {}: cannot write the PNG", path));
}

}  // namespace neopipe::apps
