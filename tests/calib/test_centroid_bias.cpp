// The centroid bias field: a smooth lean of the centroids over the image is recovered from objects
// at known places, and its held-out error is the noise that is left.

#include <gtest/gtest.h>

#include <cmath>

#include "calib/centroid_bias.hpp"
#include "sim/random.hpp"

namespace {
namespace calib = neopipe::calib;
using Eigen::Vector2d;

Vector2d lean(const Vector2d& p) {  // a quadratic field, px
  const double u = p.x() / 1279 * 2 - 1;
  const double v = p.y() / 959 * 2 - 1;
  return {-0.25 + 0.08 * u - 0.10 * v * v, -0.12 + 0.05 * v + 0.08 * u * v};
}

TEST(CentroidBias, RecoversASmoothLeanToItsNoise) {
  neopipe::sim::Random rng(3);
  std::vector<Vector2d> projected;
  std::vector<Vector2d> centroids;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      const Vector2d p(60 + 105.0 * i, 50 + 78.0 * j);
      projected.push_back(p);
      centroids.emplace_back(p + lean(p) + Vector2d(rng.normal(0, 0.01), rng.normal(0, 0.01)));
    }
  }
  const calib::CentroidBiasFit f = calib::fit_centroid_bias(centroids, projected, {1280, 960}, 2);
  for (const Vector2d& p : {Vector2d(0, 0), Vector2d(640, 480), Vector2d(1279, 959), Vector2d(300, 800)}) {
    EXPECT_LT((f.bias.at(p) - lean(p)).norm(), 0.01) << p.transpose();
  }
  EXPECT_LT(f.fit.rms, 0.016);
  EXPECT_GT(f.held_out.rms, f.fit.rms);  // a fold cannot do better than the whole
  EXPECT_LT(f.held_out.rms, 0.02);       // ~ sqrt(2) x the noise's 0.01 per axis
  EXPECT_GT(f.held_out.rms, 0.01);
  // A field of degree 1 cannot follow the lean's curvature: its held-out error says so.
  const calib::CentroidBiasFit linear = calib::fit_centroid_bias(centroids, projected, {1280, 960}, 1);
  EXPECT_GT(linear.held_out.rms, 1.5 * f.held_out.rms);
  // Correcting undoes the lean.
  EXPECT_LT((f.bias.correct(centroids[5]) - projected[5]).norm(), 0.05);
}

TEST(CentroidBias, RefusesTooFewOrMismatchedPoints) {
  const std::vector<Vector2d> few(11, Vector2d(1, 1));
  EXPECT_THROW(calib::fit_centroid_bias(few, few, {100, 100}, 2), calib::CalibrationError);
  EXPECT_THROW(calib::fit_centroid_bias(few, std::vector<Vector2d>(10), {100, 100}, 0), calib::CalibrationError);
  EXPECT_THROW(calib::CentroidBias(2, {100, 100}, Eigen::MatrixX2d::Zero(5, 2)), calib::CalibrationError);
  EXPECT_EQ(calib::CentroidBias().at({3, 4}), Vector2d::Zero());
}

}  // namespace
