#include "calib/residual_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "pipeline/media/media.hpp"

namespace neopipe::calib {
namespace {

constexpr int kSize = 900;   // canvas, px
constexpr int kMargin = 90;  // room for labels
const cv::Scalar kInk(40, 40, 40);
const cv::Scalar kArrow(30, 30, 200);
const cv::Scalar kGrid(225, 225, 225);

// 1, 2 or 5 times a power of ten, at least x.
double round_up_125(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= x) return m * p;
  }
  return 10 * p;
}

// 1, 2 or 5 times a power of ten, at most x.
double round_down_125(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * p <= x) return m * p;
  }
  return p;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.5) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kInk, 1, cv::LINE_AA);
}

}  // namespace

void write_residual_plot(const Correspondences& points, const std::vector<Eigen::Vector2d>& errors,
                         const std::string& title, const std::string& path) {
  cv::Mat img(kSize, kSize, CV_8UC3, cv::Scalar(255, 255, 255));
  Eigen::Vector2d lo(1e300, 1e300);
  Eigen::Vector2d hi(-1e300, -1e300);
  double max_error = 0;
  double sum2 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    lo = lo.cwiseMin(points[i].world);
    hi = hi.cwiseMax(points[i].world);
    max_error = std::max(max_error, errors[i].norm());
    sum2 += errors[i].squaredNorm();
  }
  if (points.empty()) lo = hi = Eigen::Vector2d::Zero();
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-6});
  const double px_per_mm = (kSize - 2.0 * kMargin) / span;
  const auto to_canvas = [&](const Eigen::Vector2d& w) {  // x right, y up
    return cv::Point2d(kMargin + (w.x() - lo.x()) * px_per_mm, kSize - kMargin - (w.y() - lo.y()) * px_per_mm);
  };
  // Grid lines every round step, labelled in mm.
  const double step = round_up_125(span / 6);
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x() + 1e-9; x += step) {
    const auto a = to_canvas({x, lo.y()});
    cv::line(img, {static_cast<int>(a.x), kMargin / 2}, {static_cast<int>(a.x), kSize - kMargin}, kGrid);
    text(img, fmt::format("{:g}", x), {static_cast<int>(a.x) - 15, kSize - kMargin + 20}, 0.4);
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y() + 1e-9; y += step) {
    const auto a = to_canvas({lo.x(), y});
    cv::line(img, {kMargin, static_cast<int>(a.y)}, {kSize - kMargin / 2, static_cast<int>(a.y)}, kGrid);
    text(img, fmt::format("{:g}", y), {10, static_cast<int>(a.y) + 5}, 0.4);
  }
  // Magnify so the longest arrow is at most about 6 % of the plot, by a round factor (never shrink).
  const double target = 0.06 * (kSize - 2.0 * kMargin) / px_per_mm;
  const double magnify = max_error > 0 ? std::max(1.0, round_down_125(target / max_error)) : 1.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto a = to_canvas(points[i].world);
    const auto b = to_canvas(points[i].world + magnify * errors[i]);
    cv::circle(img, a, 2, kInk, cv::FILLED, cv::LINE_AA);
    cv::arrowedLine(img, a, b, kArrow, 1, cv::LINE_AA, 0, 0.25);
  }
  const double rms = points.empty() ? 0 : std::sqrt(sum2 / static_cast<double>(points.size()));
  text(img, title, {kMargin, 30}, 0.6);
  text(img,
       fmt::format("workspace mm; arrows = error x {:g}; RMS {:.3f} mm, max {:.3f} mm, {} points", magnify, rms,
                   max_error, points.size()),
       {kMargin, 55}, 0.45);
  // A scale arrow: what 0.1, 1 or 10 mm of error looks like at this magnification.
  const double ref = round_up_125(std::max(max_error, 1e-6) / 2);
  const cv::Point2d s0(kSize - kMargin - ref * magnify * px_per_mm, kSize - 25);
  cv::arrowedLine(img, s0, {kSize - kMargin, kSize - 25}, kArrow, 2, cv::LINE_AA, 0, 0.2);
  text(img, fmt::format("{:g} mm error", ref), {static_cast<int>(s0.x) - 110, kSize - 20}, 0.45);
  if (!pipeline::media::write_image(path, img))
    throw CalibrationError(path + ": cannot write the residual plot (use .png)");
}

}  // namespace neopipe::calib
