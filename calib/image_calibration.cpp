#include "calib/image_calibration.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <stdexcept>

#include "calib/chessboard.hpp"
#include "calib/dot_grid_detector.hpp"
#include "calib/estimate.hpp"
#include "calib/grid_labelling.hpp"
#include "pipeline/media/media.hpp"

namespace neopipe::calib {
namespace {

// Target plane -> workspace: the first point at (X, Y), the column axis turned THETA degrees from East.
Eigen::Vector2d on_workspace(const Eigen::Vector3d& origin, const Eigen::Vector2d& target) {
  const double a = origin[2] * std::numbers::pi / 180;
  return {origin[0] + std::cos(a) * target.x() - std::sin(a) * target.y(),
          origin[1] + std::sin(a) * target.x() + std::cos(a) * target.y()};
}

cv::Mat read_gray(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw CalibrationError(path + ": no such image file");
  cv::Mat img = pipeline::media::read_image(path, pipeline::media::ImageMode::gray);
  if (img.empty()) throw CalibrationError(path + ": cannot be read as an image");
  return img;
}

}  // namespace

TargetSpec parse_target(const std::string& text) {
  static const std::regex form(R"((dots|chessboard):(\d+)x(\d+):([0-9]*\.?[0-9]+)(mm)?)");
  std::smatch m;
  if (!std::regex_match(text, m, form)) {
    throw std::invalid_argument("--target " + text +
                                ": expected dots:COLSxROWS:PITCHmm or chessboard:COLSxROWS:SQUAREmm");
  }
  TargetSpec t;
  t.dots = m[1] == "dots";
  t.cols = std::stoi(m[2]);
  t.rows = std::stoi(m[3]);
  t.pitch = std::stod(m[4]);
  if (t.cols < 2 || t.rows < 2 || t.cols * t.rows < 4 || !(t.pitch > 0)) {
    throw std::invalid_argument("--target " + text + ": needs at least 2 x 2 points and a positive pitch");
  }
  return t;
}

ImageCalibration calibrate_images(const std::vector<std::string>& images, const ImageCalibrationOptions& o) {
  if (images.empty()) throw std::invalid_argument("--target needs images of the target");
  const TargetSpec& t = o.target;
  std::vector<View> views;
  ImageCalibration out;
  std::vector<std::string> rejected;
  cv::Size size;
  for (std::size_t n = 0; n < images.size(); ++n) {
    const std::string& path = images[n];
    const cv::Mat img = read_gray(path);
    if (n == 0) size = img.size();
    if (img.size() != size) {
      throw CalibrationError(
          fmt::format("{}: {}x{} pixels, but {} is {}x{}: every view must come from the "
                      "same camera",
                      path, img.cols, img.rows, images[0], size.width, size.height));
    }
    const auto found = t.dots ? find_dot_grid(img, t.cols, t.rows) : find_chessboard(img, t.cols, t.rows);
    if (o.progress) o.progress(n + 1);
    if (!found) {
      if (n == 0) {
        throw CalibrationError(path +
                               ": the target was not found in the first image, the one lying on the "
                               "workspace");
      }
      rejected.push_back(path + ": target not found");
      continue;
    }
    View v{path, {}};
    for (int j = 0; j < t.rows; ++j) {
      for (int i = 0; i < t.cols; ++i) {
        const Eigen::Vector2d plane(i * t.pitch, j * t.pitch);
        const Eigen::Vector2d px = (*found)[grid_index(i, j, t.cols)];
        v.points.push_back({px, plane});
        if (n == 0) out.workspace.push_back({px, on_workspace(o.origin, plane)});
      }
    }
    views.push_back(std::move(v));
  }
  const bool full = o.model == "full" || (o.model == "auto" && views.size() >= 3);
  EstimateOptions estimate;
  estimate.ransac.inlier_mm = o.inlier_mm;
  out.calibration =
      full ? calibrate_full(views, out.workspace, size, estimate) : calibrate_homography(out.workspace, size, estimate);
  out.calibration.report.views_used = static_cast<int>(full ? views.size() : 1);
  out.calibration.report.views_rejected = static_cast<int>(rejected.size());
  out.calibration.report.rejected = rejected;
  return out;
}

}  // namespace neopipe::calib
