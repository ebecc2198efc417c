// Plane homographies on synthetic scenes: a camera tilted 20-40 degrees over a 500 x 500 mm plane
// that fills most of a 1280 x 960 image. Exact data must come back to rounding; noisy data as well
// as least squares allows (checked against OpenCV and against a bound from the noise); gross
// outliers must all be caught by RANSAC; degenerate input must be refused with a clear message.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <random>
#include <string>
#include <vector>

#include "calib/homography.hpp"

namespace calib = neopipe::calib;

namespace {

constexpr double kPlaneMm = 500;
constexpr double kImageWidth = 1280;
constexpr double kImageHeight = 960;
constexpr double kPixelSigma = 0.3;

/// A random pinhole camera looking at the plane's centre from 700-1000 mm, tilted 20-40 degrees
/// from the plane's normal in a random direction and rolled at random, its focal length and
/// principal point chosen so that the plane fills 90 % of the image's width or height.
Eigen::Matrix3d random_world_to_image(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double pi = std::numbers::pi;
  const double tilt = (20 + 20 * unit(rng)) * pi / 180;
  const double azimuth = 2 * pi * unit(rng);
  const double roll = 2 * pi * unit(rng);
  const double distance = 700 + 300 * unit(rng);
  const Eigen::Vector3d centre(kPlaneMm / 2, kPlaneMm / 2, 0);
  const Eigen::Vector3d position =
      centre + distance * Eigen::Vector3d(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth),
                                          std::cos(tilt));
  const Eigen::Vector3d forward = (centre - position).normalized();
  const Eigen::Vector3d side = forward.cross(Eigen::Vector3d::UnitX()).normalized();
  const Eigen::Vector3d right = Eigen::AngleAxisd(roll, forward) * side;
  Eigen::Matrix3d rotation;  // world -> camera: rows are the camera's axes
  rotation.row(0) = right;
  rotation.row(1) = forward.cross(right);
  rotation.row(2) = forward;
  const Eigen::Vector3d translation = -rotation * position;
  Eigen::Matrix3d plane_to_camera;
  plane_to_camera << rotation.col(0), rotation.col(1), translation;

  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-1e300);
  for (const double x : {0.0, kPlaneMm}) {
    for (const double y : {0.0, kPlaneMm}) {
      const Eigen::Vector2d p = (plane_to_camera * Eigen::Vector3d(x, y, 1)).hnormalized();
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  const double f = 0.9 * std::min(kImageWidth / (high.x() - low.x()), kImageHeight / (high.y() - low.y()));
  Eigen::Matrix3d k;
  k << f, 0, kImageWidth / 2 - f * (low.x() + high.x()) / 2, 0, f, kImageHeight / 2 - f * (low.y() + high.y()) / 2, 0,
      0, 1;
  return k * plane_to_camera;
}

Eigen::Matrix3d normalised(const Eigen::Matrix3d& h) {
  return h / h(2, 2);
}

struct Scene {
  Eigen::Matrix3d image_to_world;
  calib::Correspondences exact;   ///< noise-free
  calib::Correspondences points;  ///< pixels with noise (equal to exact when sigma is 0)
};

/// n world points uniform over the plane, their exact pixels, and pixels with Gaussian noise.
Scene make_scene(std::uint64_t seed, int n, double pixel_sigma) {
  std::mt19937_64 rng(seed);
  const Eigen::Matrix3d world_to_image = random_world_to_image(rng);
  Scene scene;
  scene.image_to_world = normalised(world_to_image.inverse());
  std::uniform_real_distribution<double> coordinate(0, kPlaneMm);
  std::normal_distribution<double> noise(0, pixel_sigma);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d world(coordinate(rng), coordinate(rng));
    const Eigen::Vector2d pixel = calib::apply(world_to_image, world);
    scene.exact.push_back({pixel, world});
    scene.points.push_back(
        {pixel + (pixel_sigma > 0 ? Eigen::Vector2d(noise(rng), noise(rng)) : Eigen::Vector2d::Zero()), world});
  }
  return scene;
}

double relative_difference(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return (normalised(a) - normalised(b)).norm() / normalised(b).norm();
}

/// Largest |apply(h, pixel) - world| over the points, mm.
double max_map_error(const Eigen::Matrix3d& h, const calib::Correspondences& points) {
  double worst = 0;
  for (const auto& c : points) worst = std::max(worst, (calib::apply(h, c.pixel) - c.world).norm());
  return worst;
}

/// RMS of |apply(h, pixel) - world| over the points, mm: the refinement's cost as a length.
double rms_map_error(const Eigen::Matrix3d& h, const calib::Correspondences& points) {
  double sum = 0;
  for (const auto& c : points) sum += (calib::apply(h, c.pixel) - c.world).squaredNorm();
  return std::sqrt(sum / static_cast<double>(points.size()));
}

/// RMS over the exact points of the distance between the maps a and b, mm.
double rms_map_difference(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, const calib::Correspondences& exact) {
  double sum = 0;
  for (const auto& c : exact) sum += (calib::apply(a, c.pixel) - calib::apply(b, c.pixel)).squaredNorm();
  return std::sqrt(sum / static_cast<double>(exact.size()));
}

/// The largest local stretch of the map over the points, mm/px: the largest singular value of its
/// Jacobian (A - w c^T) / z, where H = [A b; c^T 1] and w = apply(H, p).
double largest_stretch(const Eigen::Matrix3d& image_to_world, const calib::Correspondences& exact) {
  double stretch = 0;
  for (const auto& c : exact) {
    const Eigen::Vector3d q = image_to_world * c.pixel.homogeneous();
    const Eigen::Vector2d w = q.hnormalized();
    const Eigen::Matrix2d jacobian =
        (image_to_world.topLeftCorner<2, 2>() - w * image_to_world.block<1, 2>(2, 0)) / q.z();
    stretch = std::max(stretch, Eigen::JacobiSVD<Eigen::Matrix2d>(jacobian).singularValues()(0));
  }
  return stretch;
}

/// A bound on the expected RMS distance, over the data points, between a least-squares fit and the
/// truth. Linearised, the fit's error at the data is P e with P the projection onto the span of the
/// Jacobian's 8 columns and e the world-plane noise, so E|P e|^2 = tr(P C) <= 8 lambda_max(C), and the
/// mean over n points is 8 lambda_max / n. lambda_max is the largest world-plane noise variance:
/// (sigma_px times the map's largest local stretch, mm/px)^2.
double expected_fit_error_bound(const Eigen::Matrix3d& image_to_world, const calib::Correspondences& exact,
                                double pixel_sigma) {
  return pixel_sigma * largest_stretch(image_to_world, exact) * std::sqrt(8.0 / static_cast<double>(exact.size()));
}

Eigen::Matrix3d to_eigen(const cv::Mat& m) {
  Eigen::Matrix3d h;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) h(i, j) = m.at<double>(i, j);
  }
  return h;
}

struct OpenCvFit {
  Eigen::Matrix3d h;
  std::vector<bool> inlier;
};

OpenCvFit opencv_homography(const calib::Correspondences& points, int method, double threshold = 3) {
  std::vector<cv::Point2d> pixels;
  std::vector<cv::Point2d> world;
  for (const auto& c : points) {
    pixels.emplace_back(c.pixel.x(), c.pixel.y());
    world.emplace_back(c.world.x(), c.world.y());
  }
  std::vector<unsigned char> mask;
  const cv::Mat h = cv::findHomography(pixels, world, method, threshold, mask, 2000, 0.999);
  OpenCvFit fit{to_eigen(h), {}};
  for (const unsigned char m : mask) fit.inlier.push_back(m != 0);
  return fit;
}

/// The message of the CalibrationError that f throws ("" when it throws none).
template <typename F>
std::string calibration_error(F&& f) {
  try {
    f();
  } catch (const calib::CalibrationError& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(Homography, ApplyDividesByTheProjectiveDepth) {
  Eigen::Matrix3d h;
  h << 2, 0, 1, 0, 3, -1, 0.5, 0, 1;
  const Eigen::Vector2d p = calib::apply(h, {2, 4});  // (5, 11, 2)
  EXPECT_DOUBLE_EQ(p.x(), 2.5);
  EXPECT_DOUBLE_EQ(p.y(), 5.5);
}

TEST(HomographyDlt, RecoversExactRandomPerspectiveMaps) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    const Scene scene = make_scene(seed, 50, 0);
    // Real perspective: the third row is far from (0, 0, 1) on the scale of the image.
    EXPECT_GT((scene.image_to_world.block<1, 2>(2, 0).norm() * kImageWidth), 0.1);
    const Eigen::Matrix3d h = calib::fit_homography_dlt(scene.points);
    EXPECT_EQ(h(2, 2), 1.0);
    EXPECT_LT(relative_difference(h, scene.image_to_world), 1e-9);
    EXPECT_LT(max_map_error(h, scene.points), 1e-9);
    // The minimal case: 4 points, at the plane's corners (4 random points can be nearly collinear,
    // and then even exact data extrapolates to ~1e-9 mm over the plane).
    calib::Correspondences four;
    for (const Eigen::Vector2d& world : {Eigen::Vector2d(0, 0), Eigen::Vector2d(kPlaneMm, 0),
                                         Eigen::Vector2d(kPlaneMm, kPlaneMm), Eigen::Vector2d(0, kPlaneMm)}) {
      four.push_back({calib::apply(scene.image_to_world.inverse(), world), world});
    }
    const Eigen::Matrix3d h4 = calib::fit_homography_dlt(four);
    EXPECT_LT(relative_difference(h4, scene.image_to_world), 1e-9);
    EXPECT_LT(max_map_error(h4, scene.points), 1e-9);
  }
}

TEST(HomographyDlt, HartleyNormalisationKeepsLargePixelOffsetsAccurate) {
  // The same scenes seen through pixel coordinates offset by 1e4 (entries ~1 and ~1e4 * 500 side by
  // side in the DLT matrix). Normalisation centres and scales each point set first, which makes the
  // DLT exactly invariant to such a change of pixel frame: the fit on the offset pixels is the fit
  // on the original pixels composed with the shift. An un-normalised DLT loses that invariance
  // (measured: 2e-4 to 4e-3 mm on these scenes, against ~1e-12 mm here), although on exact data or
  // in accuracy against the truth it is barely worse at this offset, so it is the invariance that
  // shows the normalisation at work.
  const Eigen::Vector2d offset(1e4, 1e4);
  Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
  shift.topRightCorner<2, 1>() = -offset;  // offset pixel -> original pixel
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(seed);
    Scene exact = make_scene(seed, 50, 0);
    for (auto& c : exact.points) c.pixel += offset;
    const Eigen::Matrix3d truth = normalised(exact.image_to_world * shift);
    const Eigen::Matrix3d h = calib::fit_homography_dlt(exact.points);
    EXPECT_LT(relative_difference(h, truth), 1e-9);
    EXPECT_LT(max_map_error(h, exact.points), 1e-8);

    Scene noisy = make_scene(seed + 1000, 200, kPixelSigma);
    const Eigen::Matrix3d original_fit = calib::fit_homography_dlt(noisy.points);
    for (auto& c : noisy.points) c.pixel += offset;
    for (auto& c : noisy.exact) c.pixel += offset;
    const Eigen::Matrix3d offset_fit = calib::fit_homography_dlt(noisy.points);
    EXPECT_LT(rms_map_difference(offset_fit, original_fit * shift, noisy.exact), 1e-9);
    const double bound = expected_fit_error_bound(noisy.image_to_world * shift, noisy.exact, kPixelSigma);
    EXPECT_LT(rms_map_difference(offset_fit, noisy.image_to_world * shift, noisy.exact), 2.5 * bound);
  }
}

TEST(HomographyFit, NoisyPixelsLeastSquaresMatchesOpenCvAndTheTruth) {
  for (std::uint64_t seed = 101; seed <= 110; ++seed) {
    SCOPED_TRACE(seed);
    const Scene scene = make_scene(seed, 200, kPixelSigma);
    const double bound = expected_fit_error_bound(scene.image_to_world, scene.exact, kPixelSigma);
    const Eigen::Matrix3d dlt = calib::fit_homography_dlt(scene.points);
    const Eigen::Matrix3d refined = calib::refine_homography(dlt, scene.points);
    const Eigen::Matrix3d opencv = opencv_homography(scene.points, 0).h;

    // The refinement minimises exactly this RMS; the DLT minimises an algebraic error instead, and
    // OpenCV's method 0 runs a DLT and a few Levenberg-Marquardt steps on the same world-plane cost.
    EXPECT_LE(rms_map_error(refined, scene.points), rms_map_error(dlt, scene.points));
    EXPECT_LE(rms_map_error(refined, scene.points), rms_map_error(opencv, scene.points) * (1 + 1e-9));

    // Against the truth: both fits within 2.5 times the expected-error bound. The squared RMS error is
    // (linearised) a quadratic form in Gaussian noise with at most 8 degrees of freedom, so a
    // factor of 2.5 in RMS (6.25 in the mean square) is exceeded with probability below 1e-6.
    EXPECT_LT(rms_map_difference(dlt, scene.image_to_world, scene.exact), 2.5 * bound);
    EXPECT_LT(rms_map_difference(refined, scene.image_to_world, scene.exact), 2.5 * bound);
    // And the same least-squares optimum as OpenCV's, to a small fraction of the statistical error.
    EXPECT_LT(rms_map_difference(refined, opencv, scene.exact), 0.01 * bound);
  }
}

TEST(HomographyRefine, NeverWorseThanItsStart) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0, 1);
  for (std::uint64_t seed = 201; seed <= 210; ++seed) {
    SCOPED_TRACE(seed);
    const Scene scene = make_scene(seed, 200, kPixelSigma);
    const Eigen::Matrix3d dlt = calib::fit_homography_dlt(scene.points);
    const Eigen::Matrix3d optimum = calib::refine_homography(dlt, scene.points);
    // Starting at the optimum (or at the truth, or far away) must not make anything worse.
    std::vector<Eigen::Matrix3d> starts{dlt, optimum, scene.image_to_world, 3.0 * optimum};
    for (const double size : {1e-6, 1e-3, 1e-2, 0.1, 1.0}) {
      Eigen::Matrix3d perturbed = optimum;
      for (int i = 0; i < 8; ++i) perturbed(i / 3, i % 3) *= 1 + size * gauss(rng);
      starts.push_back(perturbed);
    }
    for (const Eigen::Matrix3d& start : starts) {
      const Eigen::Matrix3d refined = calib::refine_homography(start, scene.points);
      EXPECT_EQ(refined(2, 2), 1.0);
      // Against the start as the refinement sees it, H / H(2,2): 3 * optimum is the same map, but
      // the division rounds its entries (changing the error by ~1e-15 mm either way).
      EXPECT_LE(rms_map_error(refined, scene.points), rms_map_error(normalised(start), scene.points));
    }
    // From a start within a percent or so it reaches the same optimum.
    Eigen::Matrix3d near = optimum;
    near(0, 0) *= 1.01;
    near(2, 1) *= 0.99;
    const double bound = expected_fit_error_bound(scene.image_to_world, scene.exact, kPixelSigma);
    EXPECT_LT(rms_map_difference(calib::refine_homography(near, scene.points), optimum, scene.exact), 1e-3 * bound);
  }
}

namespace {

/// An inlier threshold that a Gaussian inlier exceeds with probability below exp(-4.5^2 / 2) = 4e-5:
/// the world-plane error of a point is at most a 2-D Gaussian with the largest local noise sigma.
double inlier_threshold(const Eigen::Matrix3d& image_to_world, const calib::Correspondences& exact,
                        double pixel_sigma) {
  return 4.5 * pixel_sigma * largest_stretch(image_to_world, exact);
}

/// Replaces a fraction of the points with gross outliers (a new random world point, or a new random
/// pixel), each at least 10 mm (four times the largest inlier threshold here, 2.5 mm) away from
/// where the true map puts it. Returns which points are still inliers.
std::vector<bool> add_gross_outliers(Scene& scene, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<bool> inlier(scene.points.size(), true);
  std::vector<std::size_t> order(scene.points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  std::uniform_real_distribution<double> world(-50, kPlaneMm + 50);
  std::uniform_real_distribution<double> u(0, kImageWidth - 1);
  std::uniform_real_distribution<double> v(0, kImageHeight - 1);
  for (int k = 0; k < count; ++k) {
    calib::Correspondence& c = scene.points[order[static_cast<std::size_t>(k)]];
    do {
      if (k % 2 == 0) {
        c.world = {world(rng), world(rng)};
      } else {
        c.pixel = {u(rng), v(rng)};
      }
    } while ((calib::apply(scene.image_to_world, c.pixel) - c.world).norm() < 10);
    inlier[order[static_cast<std::size_t>(k)]] = false;
  }
  return inlier;
}

calib::Correspondences only(const calib::Correspondences& points, const std::vector<bool>& keep) {
  calib::Correspondences out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

/// RANSAC against gross outliers: every outlier rejected, >= 99 % of the inliers kept, the map as
/// good as the least-squares fit to the true inliers alone.
void check_ransac(std::uint64_t seed, int n, int outliers) {
  Scene scene = make_scene(seed, n, kPixelSigma);
  const std::vector<bool> truly_inlier = add_gross_outliers(scene, outliers, seed + 1000);
  const double threshold = inlier_threshold(scene.image_to_world, scene.exact, kPixelSigma);
  ASSERT_LT(threshold, 2.5);
  const calib::HomographyFit fit = calib::fit_homography_ransac(scene.points, {.inlier_mm = threshold, .seed = seed});
  ASSERT_EQ(fit.inlier.size(), scene.points.size());
  EXPECT_EQ(fit.inliers, std::count(fit.inlier.begin(), fit.inlier.end(), true));
  int kept = 0;
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    if (!truly_inlier[i]) {
      EXPECT_FALSE(fit.inlier[i]) << "gross outlier " << i << " accepted";
    }
    kept += truly_inlier[i] && fit.inlier[i] ? 1 : 0;
  }
  EXPECT_GE(kept, 0.99 * (n - outliers));

  const calib::Correspondences clean = only(scene.points, truly_inlier);
  const calib::Correspondences clean_exact = only(scene.exact, truly_inlier);
  const Eigen::Matrix3d clean_fit = calib::refine_homography(calib::fit_homography_dlt(clean), clean);
  const double bound = expected_fit_error_bound(scene.image_to_world, clean_exact, kPixelSigma);
  EXPECT_LT(rms_map_difference(fit.image_to_world, scene.image_to_world, clean_exact), 2.5 * bound);
  // With the same consensus set it is the same least-squares fit.
  if (fit.inlier == truly_inlier) {
    EXPECT_LT(rms_map_difference(fit.image_to_world, clean_fit, clean_exact), 1e-3 * bound);
  }
}

}  // namespace

TEST(HomographyRansac, ThirtyPercentGrossOutliersAreAllRejected) {
  for (std::uint64_t seed = 301; seed <= 310; ++seed) {
    SCOPED_TRACE(seed);
    check_ransac(seed, 200, 60);
  }
}

TEST(HomographyRansac, AFewGrossOutliersAreAllRejected) {
  for (std::uint64_t seed = 401; seed <= 410; ++seed) {
    SCOPED_TRACE(seed);
    check_ransac(seed, 100, 3);
  }
}

TEST(HomographyRansac, WithoutOutliersEqualsTheLeastSquaresFit) {
  const Scene scene = make_scene(501, 200, kPixelSigma);
  const double threshold = inlier_threshold(scene.image_to_world, scene.exact, kPixelSigma);
  const calib::HomographyFit fit = calib::fit_homography_ransac(scene.points, {.inlier_mm = threshold});
  EXPECT_EQ(fit.inliers, 200);
  const Eigen::Matrix3d least_squares = calib::refine_homography(calib::fit_homography_dlt(scene.points), scene.points);
  const double bound = expected_fit_error_bound(scene.image_to_world, scene.exact, kPixelSigma);
  EXPECT_LT(rms_map_difference(fit.image_to_world, least_squares, scene.exact), 1e-3 * bound);
}

TEST(HomographyRansac, SameSeedSameResult) {
  Scene scene = make_scene(601, 200, kPixelSigma);
  add_gross_outliers(scene, 60, 602);
  const double threshold = inlier_threshold(scene.image_to_world, scene.exact, kPixelSigma);
  const calib::RansacOptions options{.inlier_mm = threshold, .seed = 12345};
  const calib::HomographyFit a = calib::fit_homography_ransac(scene.points, options);
  const calib::HomographyFit b = calib::fit_homography_ransac(scene.points, options);
  EXPECT_EQ(a.image_to_world, b.image_to_world);  // bit for bit
  EXPECT_EQ(a.inlier, b.inlier);
  EXPECT_EQ(a.inliers, b.inliers);
  // Another seed draws other samples but finds the same consensus.
  const calib::HomographyFit c = calib::fit_homography_ransac(scene.points, {.inlier_mm = threshold, .seed = 54321});
  EXPECT_EQ(c.inlier, a.inlier);
}

TEST(HomographyRansac, AsGoodAsOpenCvRansac) {
  const auto count = [](const std::vector<bool>& v) { return std::count(v.begin(), v.end(), true); };
  for (std::uint64_t seed = 701; seed <= 710; ++seed) {
    SCOPED_TRACE(seed);
    Scene scene = make_scene(seed, 200, kPixelSigma);
    const std::vector<bool> truly_inlier = add_gross_outliers(scene, 60, seed + 1000);
    const double threshold = inlier_threshold(scene.image_to_world, scene.exact, kPixelSigma);
    const calib::HomographyFit ours =
        calib::fit_homography_ransac(scene.points, {.inlier_mm = threshold, .seed = seed});
    const OpenCvFit theirs = opencv_homography(scene.points, cv::RANSAC, threshold);
    // Other samples, so not necessarily the same sets: the same quality. Neither accepts a gross
    // outlier; OpenCV flags by its best minimal-sample model and we by the final fit, so we keep at
    // least as many true inliers; both maps are within the statistical bound of the truth.
    std::vector<bool> ours_wrong(truly_inlier.size());
    std::vector<bool> theirs_wrong(truly_inlier.size());
    std::vector<bool> ours_right(truly_inlier.size());
    std::vector<bool> theirs_right(truly_inlier.size());
    for (std::size_t i = 0; i < truly_inlier.size(); ++i) {
      ours_wrong[i] = ours.inlier[i] && !truly_inlier[i];
      theirs_wrong[i] = theirs.inlier[i] && !truly_inlier[i];
      ours_right[i] = ours.inlier[i] && truly_inlier[i];
      theirs_right[i] = theirs.inlier[i] && truly_inlier[i];
    }
    EXPECT_EQ(count(ours_wrong), 0);
    EXPECT_EQ(count(theirs_wrong), 0);
    EXPECT_GE(count(ours_right), count(theirs_right));
    const calib::Correspondences clean_exact = only(scene.exact, truly_inlier);
    const double bound = expected_fit_error_bound(scene.image_to_world, clean_exact, kPixelSigma);
    EXPECT_LT(rms_map_difference(ours.image_to_world, scene.image_to_world, clean_exact), 2.5 * bound);
    EXPECT_LT(rms_map_difference(theirs.h, scene.image_to_world, clean_exact), 2.5 * bound);
  }
}

TEST(HomographyDegenerate, FewerThanFourPoints) {
  const Scene scene = make_scene(801, 3, 0);
  const std::string message = calibration_error([&] { calib::fit_homography_dlt(scene.points); });
  EXPECT_TRUE(contains(message, "3 correspondences, need at least 4")) << message;
  EXPECT_TRUE(contains(calibration_error([&] { calib::fit_homography_ransac(scene.points); }), "need at least 4"));
  EXPECT_TRUE(contains(calibration_error([] { calib::fit_homography_dlt({}); }), "0 correspondences"));
}

TEST(HomographyDegenerate, CollinearPoints) {
  const Scene scene = make_scene(802, 1, 0);
  calib::Correspondences points;
  for (int i = 0; i < 10; ++i) {
    const Eigen::Vector2d world(20 + 45.0 * i, 30 + 40.0 * i);  // a diagonal of the plane
    points.push_back({calib::apply(scene.image_to_world.inverse(), world), world});
  }
  const std::string message = calibration_error([&] { calib::fit_homography_dlt(points); });
  EXPECT_TRUE(contains(message, "all 10 points are collinear in the image")) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_TRUE(contains(calibration_error([&] { calib::fit_homography_ransac(points); }), "collinear")) << message;
  // Collinear in the world plane only (the pixels are fine): the same refusal, naming the plane.
  calib::Correspondences world_only = points;
  for (std::size_t i = 0; i < world_only.size(); ++i) world_only[i].pixel = {100.0 + 37 * i, 50.0 + (i * i) % 7 * 90};
  EXPECT_TRUE(contains(calibration_error([&] { calib::fit_homography_dlt(world_only); }),
                       "all 10 points are collinear in the world plane"));
}

TEST(HomographyDegenerate, FourPointsThreeCollinear) {
  const Eigen::Matrix3d world_to_image = make_scene(803, 1, 0).image_to_world.inverse();
  calib::Correspondences points;
  for (const Eigen::Vector2d& world :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(100, 100), Eigen::Vector2d(300, 300), Eigen::Vector2d(400, 0)}) {
    points.push_back({calib::apply(world_to_image, world), world});
  }
  const std::string message = calibration_error([&] { calib::fit_homography_dlt(points); });
  EXPECT_TRUE(contains(message, "3 of 4 points are collinear")) << message;
  // The same with many points: all but one on a line still fixes only 7 of the 8 degrees of freedom.
  for (int i = 1; i <= 6; ++i) {
    const Eigen::Vector2d world(50.0 * i + 25, 50.0 * i + 25);
    points.push_back({calib::apply(world_to_image, world), world});
  }
  EXPECT_TRUE(contains(calibration_error([&] { calib::fit_homography_dlt(points); }), "9 of 10 points are collinear"));
  // One more point off the line makes it well posed again.
  points.push_back({calib::apply(world_to_image, {0, 400}), {0, 400}});
  EXPECT_LT(max_map_error(calib::fit_homography_dlt(points), points), 1e-9);
}

TEST(HomographyDegenerate, DuplicatedPoints) {
  const Scene scene = make_scene(804, 4, 0);
  calib::Correspondences points = scene.points;
  points[3] = points[1];  // only 3 distinct correspondences left
  std::string message = calibration_error([&] { calib::fit_homography_dlt(points); });
  EXPECT_TRUE(contains(message, "2 of 4 points coincide in the image (first #1 and #3")) << message;
  // A duplicate among many is refused too: one detection claimed twice is a bug upstream.
  const Scene large = make_scene(805, 30, 0);
  points = large.points;
  points[20].pixel = points[7].pixel;
  message = calibration_error([&] { calib::fit_homography_dlt(points); });
  EXPECT_TRUE(contains(message, "2 of 30 points coincide in the image (first #7 and #20")) << message;
  points = large.points;
  points[5].world = points[9].world;
  points[12].world = points[9].world;
  message = calibration_error([&] { calib::fit_homography_dlt(points); });
  EXPECT_TRUE(contains(message, "3 of 30 points coincide in the world plane (first #5 and #9")) << message;
  // RANSAC treats a duplicate as just another point.
  points = large.points;
  points.push_back(points[0]);
  EXPECT_EQ(calib::fit_homography_ransac(points).inliers, 31);
}

TEST(HomographyDegenerate, NearlyCollinearButValidPointsAreAccepted) {
  const Eigen::Matrix3d world_to_image = make_scene(806, 1, 0).image_to_world.inverse();
  // Ten points along a diagonal, alternately 1 mm either side of it: nearly collinear (the spread
  // across the line is 1/300 of the spread along it) but exact, so the map is determined.
  calib::Correspondences points;
  for (int i = 0; i < 10; ++i) {
    const double along = 25 + 50.0 * i;
    const double across = i % 2 == 0 ? 1.0 : -1.0;
    const Eigen::Vector2d world(along + across, along - across);
    points.push_back({calib::apply(world_to_image, world), world});
  }
  const Eigen::Matrix3d h = calib::fit_homography_dlt(points);
  EXPECT_LT(relative_difference(h, world_to_image.inverse()), 1e-6);
  EXPECT_LT(max_map_error(h, points), 1e-9);
}

TEST(HomographyDegenerate, RansacWithoutAUsableSample) {
  // A convex quadrilateral seen as a bow-tie: every triangle is fine, but two keep their orientation
  // and two flip, which no camera can produce (the map would cross the vanishing line).
  const calib::Correspondences points{
      {{0, 0}, {0, 0}}, {{100, 0}, {100, 0}}, {{100, 100}, {0, 100}}, {{0, 100}, {100, 100}}};
  const std::string message = calibration_error([&] { calib::fit_homography_ransac(points); });
  EXPECT_TRUE(contains(message, "no usable 4-point sample among 4 points")) << message;
}

TEST(HomographyDegenerate, RansacRejectsBadOptions) {
  const Scene scene = make_scene(807, 20, 0);
  for (const calib::RansacOptions& options :
       {calib::RansacOptions{.inlier_mm = 0}, calib::RansacOptions{.iterations = 0},
        calib::RansacOptions{.confidence = 1}}) {
    EXPECT_TRUE(
        contains(calibration_error([&] { calib::fit_homography_ransac(scene.points, options); }), "bad options"));
  }
}

TEST(HomographyRefine, RefusesAStartWithoutH22) {
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
  h(2, 2) = 0;
  const Scene scene = make_scene(808, 20, 0);
  EXPECT_TRUE(contains(calibration_error([&] { calib::refine_homography(h, scene.points); }), "H(2,2) is 0"));
}
