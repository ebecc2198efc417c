#include "calib/calibration.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>
#include <optional>
#include <string_view>
#include <utility>

#include "calib/homography.hpp"

namespace neopipe::calib {
namespace {

cv::Mat to_cv(const Eigen::Matrix3d& m) {
  cv::Mat out(3, 3, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out.at<double>(i, j) = m(i, j);
  }
  return out;
}

void write_stats(cv::FileStorage& fs, const std::string& prefix, const ErrorStats& s) {
  fs << prefix + "_mean_mm" << std::vector<double>{s.mean.x(), s.mean.y()};
  fs << prefix + "_sd_mm" << std::vector<double>{s.sd.x(), s.sd.y()};
  fs << prefix + "_rms_mm" << s.rms << prefix + "_max_mm" << s.max << prefix + "_points" << s.points;
}

// Reads calibration files with yaml-cpp, not with the cv::FileStorage that writes them: on malformed
// files OpenCV 4.6's readers loop for ever (YAML: when the first collection ends before the file and
// a lone '-' follows, as in "%YAML:1.0\n a:1\nb---\n"), dereference a null pointer (XML, which it
// takes whatever the file's name), throw std::length_error (a key with nothing before its colon,
// after reading a byte before its buffer: OpenCV issue 28619) and allocate what a matrix declares
// before looking at its data (a 'cols' that is not a number reads as INT_MAX: 16 GiB). All were
// found by fuzz/fuzz_calibration.cpp; a hang or a crash cannot be caught. This reads the YAML
// OpenCV writes: "%YAML:1.0" (a directive yaml-cpp ignores), keys, "!!opencv-matrix" maps.
class CalibrationReader {
 public:
  CalibrationReader(std::string path, YAML::Node root) : path_(std::move(path)), root_(std::move(root)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw CalibrationError(fmt::format("{}: missing or malformed '{}' ({})", path_, key, what));
  }
  const YAML::Node& root() const { return root_; }

  /// A number, or nullopt if the key is absent; `what` describes it in the message otherwise.
  std::optional<double> number(const std::string& key, const std::string& what) const {
    const YAML::Node n = root_[key];
    if (!n) return std::nullopt;
    const auto v = to_number(n);
    if (!v) fail(key, what);
    return v;
  }
  std::optional<int> integer(const std::string& key) const {
    const YAML::Node n = root_[key];
    if (!n) return std::nullopt;
    const auto v = to_integer(n);
    if (!v) fail(key, "a whole number");
    return v;
  }
  /// [a, b]; nullopt if absent.
  std::optional<std::pair<double, double>> pair(const std::string& key) const {
    const YAML::Node n = root_[key];
    if (!n) return std::nullopt;
    if (!n.IsSequence() || n.size() != 2) fail(key, "two numbers [a, b]");
    const auto a = to_number(n[0]);
    const auto b = to_number(n[1]);
    if (!a || !b) fail(key, "two numbers [a, b]");
    return std::pair{*a, *b};
  }

  /// An "!!opencv-matrix" (rows, cols, dt, data) as a one-channel CV_64F matrix; empty if the key is
  /// absent. Its elements are what OpenCV would hold in the declared type, then as doubles.
  cv::Mat matrix(const std::string& key) const {
    const YAML::Node n = root_[key];
    if (!n) return {};
    constexpr int kMaxSide = 16;  // 3x3 matrices, at most 14 distortion coefficients
    const std::string what = "a matrix: rows, cols, dt (one of u c w s i f d) and data";
    if (!n.IsMap() || !n["rows"] || !n["cols"] || !n["dt"] || !n["data"]) fail(key, what);
    const auto rows = to_integer(n["rows"]);
    const auto cols = to_integer(n["cols"]);
    if (!rows || !cols || *rows < 0 || *cols < 0 || *rows > kMaxSide || *cols > kMaxSide) fail(key, what);
    const YAML::Node dt = n["dt"];
    if (!dt.IsScalar() || dt.Scalar().size() != 1 ||
        std::string_view("ucwsifd").find(dt.Scalar()[0]) == std::string_view::npos) {
      fail(key, what);
    }
    const YAML::Node data = n["data"];
    if (!data.IsSequence() || data.size() != static_cast<std::size_t>(*rows * *cols)) {
      fail(key, fmt::format("data must hold rows x cols = {} numbers", *rows * *cols));
    }
    cv::Mat m(*rows, *cols, CV_64F);
    for (int i = 0; i < *rows * *cols; ++i) {
      const auto v = to_number(data[static_cast<std::size_t>(i)]);
      if (!v) fail(key, fmt::format("data element {} is not a number", i));
      m.at<double>(i / *cols, i % *cols) = as_stored(*v, dt.Scalar()[0]);
    }
    return m;
  }

 private:
  // A number as OpenCV writes it, ".Nan", ".Inf" and "-.Inf" included (yaml-cpp spells them otherwise).
  static std::optional<double> to_number(const YAML::Node& n) {
    if (!n.IsScalar()) return std::nullopt;
    const std::string& s = n.Scalar();
    if (s == ".Nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == ".Inf" || s == "+.Inf") return std::numeric_limits<double>::infinity();
    if (s == "-.Inf") return -std::numeric_limits<double>::infinity();
    try {
      return n.as<double>();
    } catch (const YAML::Exception&) {
      return std::nullopt;
    }
  }
  static std::optional<int> to_integer(const YAML::Node& n) {
    if (!n.IsScalar()) return std::nullopt;
    try {
      return n.as<int>();
    } catch (const YAML::Exception&) {
      return std::nullopt;
    }
  }
  // What a matrix of OpenCV type `dt` holds for the value written (integers saturate and round).
  static double as_stored(double v, char dt) {
    switch (dt) {
      case 'u':
        return cv::saturate_cast<uchar>(v);
      case 'c':
        return cv::saturate_cast<schar>(v);
      case 'w':
        return cv::saturate_cast<ushort>(v);
      case 's':
        return cv::saturate_cast<short>(v);
      case 'i':
        return cv::saturate_cast<int>(v);
      case 'f':
        return static_cast<float>(v);
      default:
        return v;
    }
  }

  std::string path_;
  YAML::Node root_;
};

void read_stats(const CalibrationReader& read, const std::string& prefix, ErrorStats& s) {
  if (const auto mean = read.pair(prefix + "_mean_mm")) s.mean = {mean->first, mean->second};
  if (const auto sd = read.pair(prefix + "_sd_mm")) s.sd = {sd->first, sd->second};
  s.rms = read.number(prefix + "_rms_mm", "a number").value_or(s.rms);
  s.max = read.number(prefix + "_max_mm", "a number").value_or(s.max);
  s.points = read.integer(prefix + "_points").value_or(s.points);
}

}  // namespace

std::string model_name(Model m) {
  return m == Model::full ? "full" : "homography";
}

ErrorStats error_stats(const std::vector<Eigen::Vector2d>& errors) {
  ErrorStats s;
  s.points = static_cast<int>(errors.size());
  if (errors.empty()) return s;
  double sum2 = 0;
  for (const auto& e : errors) {
    s.mean += e;
    sum2 += e.squaredNorm();
    s.max = std::max(s.max, e.norm());
  }
  const auto n = static_cast<double>(errors.size());
  s.mean /= n;
  s.rms = std::sqrt(sum2 / n);
  if (errors.size() > 1) {
    Eigen::Vector2d var = Eigen::Vector2d::Zero();
    for (const auto& e : errors) var += (e - s.mean).cwiseAbs2();
    s.sd = (var / (n - 1)).cwiseSqrt();
  }
  return s;
}

std::vector<Eigen::Vector2d> Calibration::to_world(const std::vector<Eigen::Vector2d>& pixels) const {
  std::vector<Eigen::Vector2d> out;
  out.reserve(pixels.size());
  if (model == Model::homography) {
    for (const auto& p : pixels) out.push_back(apply(image_to_world, p));
    return out;
  }
  if (pixels.empty()) return out;
  std::vector<cv::Point2d> in;
  in.reserve(pixels.size());
  for (const auto& p : pixels) in.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> undistorted;
  // Back into pixel units (P = K), where image_to_world was fitted. The default 5 iterations leave
  // ~0.01 px at this distortion's corners; 20 and a 1e-10 tolerance put it far below the noise.
  cv::undistortPoints(in, undistorted, camera_matrix, distortion_coefficients, cv::noArray(), camera_matrix,
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-10));
  for (const auto& u : undistorted) out.push_back(apply(image_to_world, {u.x, u.y}));
  return out;
}

std::vector<Eigen::Vector2d> Calibration::to_pixel(const std::vector<Eigen::Vector2d>& world) const {
  const Eigen::Matrix3d world_to_image = image_to_world.inverse();
  std::vector<Eigen::Vector2d> out;
  out.reserve(world.size());
  if (model == Model::homography) {
    for (const auto& w : world) out.push_back(apply(world_to_image, w));
    return out;
  }
  if (world.empty()) return out;
  // Undistorted pixel -> normalised ray -> through the lens with zero rotation and translation.
  const Eigen::Matrix3d k_inv = [&] {
    Eigen::Matrix3d k;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) k(i, j) = camera_matrix.at<double>(i, j);
    }
    return Eigen::Matrix3d(k.inverse());
  }();
  std::vector<cv::Point3d> rays;
  for (const auto& w : world) {
    const Eigen::Vector2d u = apply(world_to_image, w);
    const Eigen::Vector3d n = k_inv * Eigen::Vector3d(u.x(), u.y(), 1);
    rays.emplace_back(n.x() / n.z(), n.y() / n.z(), 1);
  }
  std::vector<cv::Point2d> px;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix, distortion_coefficients, px);
  for (const auto& p : px) out.emplace_back(p.x, p.y);
  return out;
}

void save_calibration(const Calibration& c, const std::string& path) {
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::WRITE);
  } catch (const cv::Exception&) {
  }
  if (!fs.isOpened()) throw CalibrationError(path + ": cannot be written");
  fs.writeComment(
      "neopipe calibration: workspace (X, Y, 1) ~ image_to_world * (u, v, 1); for model 'full' the"
      " pixel is first undistorted with camera_matrix and distortion_coefficients.");
  fs << "model" << model_name(c.model);
  fs << "image_size" << c.image_size;
  if (c.model == Model::full) {
    fs << "camera_matrix" << c.camera_matrix << "distortion_coefficients" << c.distortion_coefficients;
  }
  fs << "image_to_world" << to_cv(c.image_to_world);
  const auto& r = c.report;
  fs << "reprojection_rms_px" << r.reprojection_rms_px;
  write_stats(fs, "fit", r.fit);
  write_stats(fs, "held_out", r.held_out);
  fs << "homography_held_out_rms_mm" << r.homography_held_out_rms << "full_held_out_rms_mm" << r.full_held_out_rms;
  fs << "views_used" << r.views_used << "views_rejected" << r.views_rejected;
  fs << "points_used" << r.points_used << "points_rejected" << r.points_rejected;
}

Calibration load_calibration(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw CalibrationError(path + ": no such calibration file");
  YAML::Node loaded;
  try {
    loaded = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw CalibrationError(path + ": cannot be read");
  } catch (const YAML::Exception& e) {
    throw CalibrationError(
        fmt::format("{}:{}:{}: not a calibration file (YAML: {})", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  const YAML::Node root = loaded;  // const: looking a key up must not add it
  if (!root.IsMap()) throw CalibrationError(path + ": not a calibration file (not a map of keys)");
  const CalibrationReader read(path, root);
  Calibration c;
  const YAML::Node model = root["model"];
  if (!model || !model.IsScalar() || (model.Scalar() != "homography" && model.Scalar() != "full")) {
    read.fail("model", "homography or full");
  }
  c.model = model.Scalar() == "full" ? Model::full : Model::homography;
  const YAML::Node size = root["image_size"];
  if (!size || !size.IsSequence() || size.size() != 2) read.fail("image_size", "[width, height]");
  try {
    c.image_size = {size[0].as<int>(), size[1].as<int>()};
  } catch (const YAML::Exception&) {
    read.fail("image_size", "[width, height]");
  }
  // 0 x 0: unknown (a calibration from point pairs without --image-size).
  if (c.image_size.width < 0 || c.image_size.height < 0 || (c.image_size.width == 0) != (c.image_size.height == 0)) {
    read.fail("image_size", "[width, height]");
  }
  const cv::Mat h = read.matrix("image_to_world");
  if (h.rows != 3 || h.cols != 3) read.fail("image_to_world", "a 3x3 matrix");
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c.image_to_world(i, j) = h.at<double>(i, j);
  }
  if (!c.image_to_world.allFinite() || std::abs(c.image_to_world.determinant()) < 1e-300) {
    read.fail("image_to_world", "an invertible 3x3 matrix");
  }
  if (c.model == Model::full) {
    c.camera_matrix = read.matrix("camera_matrix");
    if (c.camera_matrix.rows != 3 || c.camera_matrix.cols != 3) read.fail("camera_matrix", "a 3x3 matrix");
    c.distortion_coefficients = read.matrix("distortion_coefficients");
    const auto n = c.distortion_coefficients.total();
    if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
      read.fail("distortion_coefficients", "4, 5, 8, 12 or 14 numbers");
    }
  }
  auto& r = c.report;
  r.reprojection_rms_px = read.number("reprojection_rms_px", "a number").value_or(r.reprojection_rms_px);
  read_stats(read, "fit", r.fit);
  read_stats(read, "held_out", r.held_out);
  r.homography_held_out_rms = read.number("homography_held_out_rms_mm", "a number").value_or(r.homography_held_out_rms);
  r.full_held_out_rms = read.number("full_held_out_rms_mm", "a number").value_or(r.full_held_out_rms);
  r.views_used = read.integer("views_used").value_or(r.views_used);
  r.views_rejected = read.integer("views_rejected").value_or(r.views_rejected);
  r.points_used = read.integer("points_used").value_or(r.points_used);
  r.points_rejected = read.integer("points_rejected").value_or(r.points_rejected);
  return c;
}

}  // namespace neopipe::calib
