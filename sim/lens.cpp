#include "sim/lens.hpp"

#include <Eigen/LU>  // determinant()
#include <cmath>
#include <numbers>

namespace neopipe::sim {

Eigen::Vector2d distort(const Lens& lens, const Eigen::Vector2d& n) {
  const auto& d = lens.opencv;
  const auto& e = lens.extra;
  const double x = n.x();
  const double y = n.y();
  const double r2 = x * x + y * y;
  const double r4 = r2 * r2;
  const double radial = 1 + r2 * (d[0] + r2 * (d[1] + r2 * (d[4] + r2 * e.k4)));
  return {x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x) + e.s1 * r2 + e.s2 * r4,
          y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y + e.s3 * r2 + e.s4 * r4};
}

Eigen::Matrix2d distortion_jacobian(const Lens& lens, const Eigen::Vector2d& n) {
  const auto& d = lens.opencv;
  const auto& e = lens.extra;
  const double x = n.x();
  const double y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (d[0] + r2 * (d[1] + r2 * (d[4] + r2 * e.k4)));
  // d radial / d r2, and d r2 / dx = 2x.
  const double dradial = d[0] + r2 * (2 * d[1] + r2 * (3 * d[4] + r2 * 4 * e.k4));
  const double prism_x = e.s1 + 2 * e.s2 * r2;  // d(s1 r^2 + s2 r^4) / d r2
  const double prism_y = e.s3 + 2 * e.s4 * r2;
  Eigen::Matrix2d j;
  j(0, 0) = radial + x * dradial * 2 * x + 2 * d[2] * y + d[3] * 6 * x + prism_x * 2 * x;
  j(0, 1) = x * dradial * 2 * y + 2 * d[2] * x + d[3] * 2 * y + prism_x * 2 * y;
  j(1, 0) = y * dradial * 2 * x + d[2] * 2 * x + 2 * d[3] * y + prism_y * 2 * x;
  j(1, 1) = radial + y * dradial * 2 * y + d[2] * 6 * y + 2 * d[3] * x + prism_y * 2 * y;
  return j;
}

Eigen::Vector2d undistort(const Lens& lens, const Eigen::Vector2d& distorted, const Eigen::Vector2d& start,
                          double tolerance) {
  Eigen::Vector2d n = start;
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector2d f = distort(lens, n) - distorted;
    const Eigen::Matrix2d j = distortion_jacobian(lens, n);
    // The 2 x 2 solve in closed form: an unfolded lens keeps the determinant well away from 0.
    const double det = j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0);
    const Eigen::Vector2d step((j(1, 1) * f.x() - j(0, 1) * f.y()) / det, (j(0, 0) * f.y() - j(1, 0) * f.x()) / det);
    n -= step;
    if (step.squaredNorm() < tolerance * tolerance) break;
  }
  return n;
}

std::optional<double> lens_fold_radius(const Lens& lens, double field) {
  // Rays from the centre every 5 degrees, sampled every 1/400 of the field: a fold needs the
  // distortion's terms to fight over a range of radii, far wider than these steps.
  constexpr int kDirections = 72;
  constexpr int kSteps = 400;
  std::optional<double> fold;
  for (int a = 0; a < kDirections; ++a) {
    const double angle = 2 * std::numbers::pi * a / kDirections;
    const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
    double previous = 0;
    for (int s = 1; s <= kSteps; ++s) {
      const double r = field * s / kSteps;
      if (fold && r >= *fold) break;
      const Eigen::Vector2d n = r * dir;
      const double radius = distort(lens, n).dot(dir);  // along the ray: must keep growing
      if (distortion_jacobian(lens, n).determinant() <= 0 || radius <= previous) {
        fold = r;
        break;
      }
      previous = radius;
    }
  }
  return fold;
}

}  // namespace neopipe::sim
