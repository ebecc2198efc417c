#include "calib/calibration.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>

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

void read_stats(const cv::FileStorage& fs, const std::string& prefix, ErrorStats& s) {
  std::vector<double> v;
  fs[prefix + "_mean_mm"] >> v;
  if (v.size() == 2) s.mean = {v[0], v[1]};
  v.clear();
  fs[prefix + "_sd_mm"] >> v;
  if (v.size() == 2) s.sd = {v[0], v[1]};
  fs[prefix + "_rms_mm"] >> s.rms;
  fs[prefix + "_max_mm"] >> s.max;
  fs[prefix + "_points"] >> s.points;
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
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw CalibrationError(path + ": not a calibration file (OpenCV cannot parse it)");
  }
  if (!fs.isOpened()) throw CalibrationError(path + ": cannot be read");
  Calibration c;
  const auto missing = [&](const std::string& key, const std::string& what) {
    return CalibrationError(fmt::format("{}: missing or malformed '{}' ({})", path, key, what));
  };
  std::string model;
  if (fs["model"].isString()) fs["model"] >> model;
  if (model != "homography" && model != "full") throw missing("model", "homography or full");
  c.model = model == "full" ? Model::full : Model::homography;
  if (fs["image_size"].empty()) throw missing("image_size", "[width, height]");
  fs["image_size"] >> c.image_size;
  // 0 x 0: unknown (a calibration from point pairs without --image-size).
  if (c.image_size.width < 0 || c.image_size.height < 0 || (c.image_size.width == 0) != (c.image_size.height == 0)) {
    throw missing("image_size", "[width, height]");
  }
  cv::Mat h;
  fs["image_to_world"] >> h;
  if (h.rows != 3 || h.cols != 3) throw missing("image_to_world", "a 3x3 matrix");
  h.convertTo(h, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c.image_to_world(i, j) = h.at<double>(i, j);
  }
  if (!c.image_to_world.allFinite() || std::abs(c.image_to_world.determinant()) < 1e-300) {
    throw missing("image_to_world", "an invertible 3x3 matrix");
  }
  if (c.model == Model::full) {
    fs["camera_matrix"] >> c.camera_matrix;
    if (c.camera_matrix.rows != 3 || c.camera_matrix.cols != 3) throw missing("camera_matrix", "a 3x3 matrix");
    c.camera_matrix.convertTo(c.camera_matrix, CV_64F);
    fs["distortion_coefficients"] >> c.distortion_coefficients;
    const auto n = c.distortion_coefficients.total();
    if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
      throw missing("distortion_coefficients", "4, 5, 8, 12 or 14 numbers");
    }
    c.distortion_coefficients.convertTo(c.distortion_coefficients, CV_64F);
  }
  auto& r = c.report;
  fs["reprojection_rms_px"] >> r.reprojection_rms_px;
  read_stats(fs, "fit", r.fit);
  read_stats(fs, "held_out", r.held_out);
  fs["homography_held_out_rms_mm"] >> r.homography_held_out_rms;
  fs["full_held_out_rms_mm"] >> r.full_held_out_rms;
  fs["views_used"] >> r.views_used;
  fs["views_rejected"] >> r.views_rejected;
  fs["points_used"] >> r.points_used;
  fs["points_rejected"] >> r.points_rejected;
  return c;
}

}  // namespace neopipe::calib
