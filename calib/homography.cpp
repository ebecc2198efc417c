#include "calib/homography.hpp"

// Placeholder: the estimator arrives on branch calib-homography.
namespace neopipe::calib {
Eigen::Vector2d apply(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1);
  return q.head<2>() / q.z();
}
}  // namespace neopipe::calib
