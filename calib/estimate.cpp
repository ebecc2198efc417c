#include "calib/estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

namespace neopipe::calib {
namespace {

constexpr int kMinFullViews = 3;

// Fold of point i: interleaved, so each fold spreads over the whole target.
int fold_of(std::size_t i, int folds) {
  return static_cast<int>(i % static_cast<std::size_t>(folds));
}

Correspondences inliers_of(const Correspondences& points, const HomographyFit& fit) {
  Correspondences out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (fit.inlier[i]) out.push_back(points[i]);
  }
  return out;
}

std::vector<Eigen::Vector2d> errors_of(const Calibration& c, const Correspondences& points) {
  std::vector<Eigen::Vector2d> pixels;
  for (const auto& p : points) pixels.push_back(p.pixel);
  const auto mapped = c.to_world(pixels);
  std::vector<Eigen::Vector2d> errors;
  for (std::size_t i = 0; i < points.size(); ++i) errors.emplace_back(mapped[i] - points[i].world);
  return errors;
}

double reprojection_rms(const Calibration& c, const Correspondences& points) {
  std::vector<Eigen::Vector2d> world;
  for (const auto& p : points) world.push_back(p.world);
  const auto px = c.to_pixel(world);
  double sum2 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) sum2 += (px[i] - points[i].pixel).squaredNorm();
  return points.empty() ? 0 : std::sqrt(sum2 / static_cast<double>(points.size()));
}

Eigen::Matrix3d plain_homography(const Correspondences& points) {
  return refine_homography(fit_homography_dlt(points), points);
}

// k-fold: each point predicted by a homography fitted to the folds it is not in.
ErrorStats homography_held_out(const Correspondences& points, int folds) {
  std::vector<Eigen::Vector2d> errors;
  for (int f = 0; f < folds; ++f) {
    Correspondences train;
    Correspondences test;
    for (std::size_t i = 0; i < points.size(); ++i) (fold_of(i, folds) == f ? test : train).push_back(points[i]);
    if (test.empty() || train.size() < 4) continue;
    const Eigen::Matrix3d h = plain_homography(train);
    for (const auto& p : test) errors.emplace_back(apply(h, p.pixel) - p.world);
  }
  return error_stats(errors);
}

struct Intrinsics {
  cv::Mat k;
  cv::Mat d;
  double rms = 0;
};

Intrinsics calibrate_camera(const std::vector<Correspondences>& views, cv::Size size) {
  std::vector<std::vector<cv::Point3f>> objects;
  std::vector<std::vector<cv::Point2f>> images;
  for (const auto& v : views) {
    auto& o = objects.emplace_back();
    auto& im = images.emplace_back();
    for (const auto& p : v) {
      o.emplace_back(static_cast<float>(p.world.x()), static_cast<float>(p.world.y()), 0.0F);
      im.emplace_back(static_cast<float>(p.pixel.x()), static_cast<float>(p.pixel.y()));
    }
  }
  Intrinsics in;
  std::vector<cv::Mat> rvecs;
  std::vector<cv::Mat> tvecs;
  try {
    in.rms = cv::calibrateCamera(objects, images, size, in.k, in.d, rvecs, tvecs);
  } catch (const cv::Exception& e) {
    throw CalibrationError(std::string("cv::calibrateCamera failed: ") + e.err);
  }
  return in;
}

std::vector<Eigen::Vector2d> undistort(const Intrinsics& in, const Correspondences& points) {
  std::vector<cv::Point2d> px;
  for (const auto& p : points) px.emplace_back(p.pixel.x(), p.pixel.y());
  std::vector<cv::Point2d> u;
  if (!px.empty()) {
    cv::undistortPoints(px, u, in.k, in.d, cv::noArray(), in.k,
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-10));
  }
  std::vector<Eigen::Vector2d> out;
  out.reserve(u.size());
  for (const auto& q : u) out.emplace_back(q.x, q.y);
  return out;
}

Correspondences with_pixels(const Correspondences& points, const std::vector<Eigen::Vector2d>& pixels) {
  Correspondences out = points;
  for (std::size_t i = 0; i < out.size(); ++i) out[i].pixel = pixels[i];
  return out;
}

}  // namespace

Calibration calibrate_homography(const Correspondences& workspace, cv::Size image_size, const EstimateOptions& o) {
  const HomographyFit fit = fit_homography_ransac(workspace, o.ransac);
  const Correspondences used = inliers_of(workspace, fit);
  Calibration c;
  c.model = Model::homography;
  c.image_size = image_size;
  c.image_to_world = fit.image_to_world;
  auto& r = c.report;
  r.points_used = static_cast<int>(used.size());
  r.points_rejected = static_cast<int>(workspace.size() - used.size());
  r.fit = error_stats(errors_of(c, used));
  r.held_out = homography_held_out(used, o.folds);
  r.homography_held_out_rms = r.held_out.rms;
  r.reprojection_rms_px = reprojection_rms(c, used);
  r.views_used = 1;
  return c;
}

Calibration calibrate_full(const std::vector<View>& views, const Correspondences& workspace, cv::Size image_size,
                           const EstimateOptions& o) {
  if (static_cast<int>(views.size()) < kMinFullViews) {
    throw CalibrationError(
        fmt::format("the full model needs at least {} views of the target, got {} (or use the "
                    "homography model)",
                    kMinFullViews, views.size()));
  }
  std::vector<Correspondences> all;
  all.reserve(views.size());
  for (const auto& v : views) all.push_back(v.points);
  const Intrinsics in = calibrate_camera(all, image_size);

  Calibration c;
  c.model = Model::full;
  c.image_size = image_size;
  c.camera_matrix = in.k;
  c.distortion_coefficients = in.d;
  const Correspondences straight = with_pixels(workspace, undistort(in, workspace));
  const HomographyFit fit = fit_homography_ransac(straight, o.ransac);
  c.image_to_world = fit.image_to_world;
  const Correspondences used = inliers_of(workspace, fit);
  auto& r = c.report;
  r.views_used = static_cast<int>(views.size());
  r.points_used = static_cast<int>(used.size());
  r.points_rejected = static_cast<int>(workspace.size() - used.size());
  r.fit = error_stats(errors_of(c, used));
  r.reprojection_rms_px = in.rms;  // over every view, as cv::calibrateCamera reports it

  // Held out: the lens and the plane both fitted without the fold's points (the workspace view's
  // points outside the fold stay in the lens fit, the other views too).
  std::vector<Eigen::Vector2d> errors;
  for (int f = 0; f < o.folds; ++f) {
    Correspondences train;
    Correspondences test;
    for (std::size_t i = 0; i < used.size(); ++i) (fold_of(i, o.folds) == f ? test : train).push_back(used[i]);
    if (test.empty() || train.size() < 4) continue;
    std::vector<Correspondences> lens_views = all;
    lens_views.push_back(train);           // the workspace view, less the fold, in workspace coordinates
    lens_views.erase(lens_views.begin());  // views[0] is the workspace view in target coordinates
    const Intrinsics fold_in = calibrate_camera(lens_views, image_size);
    const Eigen::Matrix3d h = plain_homography(with_pixels(train, undistort(fold_in, train)));
    const auto test_px = undistort(fold_in, test);
    for (std::size_t i = 0; i < test.size(); ++i) errors.emplace_back(apply(h, test_px[i]) - test[i].world);
  }
  r.held_out = error_stats(errors);
  r.full_held_out_rms = r.held_out.rms;
  r.homography_held_out_rms = homography_held_out(used, o.folds).rms;
  return c;
}

}  // namespace neopipe::calib
