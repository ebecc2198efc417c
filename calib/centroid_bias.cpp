#include "calib/centroid_bias.hpp"

#include <Eigen/Cholesky>
#include <string>

#include "calib/correspondence.hpp"

namespace neopipe::calib {

CentroidBias::CentroidBias(int degree, cv::Size size, Eigen::MatrixX2d coefficients)
    : degree_(degree), size_(size), coefficients_(std::move(coefficients)) {
  if (degree < 0 || coefficients_.rows() != terms(degree)) {
    throw CalibrationError("centroid bias: " + std::to_string(coefficients_.rows()) + " coefficients for degree " +
                           std::to_string(degree) + " (needs " + std::to_string(terms(degree)) + ")");
  }
}

Eigen::VectorXd CentroidBias::monomials(const Eigen::Vector2d& p) const {
  // Normalised so that the coefficients of every degree are of the same size.
  const double u = size_.width > 1 ? 2 * p.x() / (size_.width - 1) - 1 : 0;
  const double v = size_.height > 1 ? 2 * p.y() / (size_.height - 1) - 1 : 0;
  Eigen::VectorXd m(terms(degree_));
  int k = 0;
  for (int d = 0; d <= degree_; ++d) {
    for (int i = 0; i <= d; ++i) m(k++) = std::pow(u, d - i) * std::pow(v, i);
  }
  return m;
}

Eigen::Vector2d CentroidBias::at(const Eigen::Vector2d& p) const {
  if (empty()) return Eigen::Vector2d::Zero();
  return coefficients_.transpose() * monomials(p);
}

namespace {

CentroidBias solve(const std::vector<Eigen::Vector2d>& centroids, const std::vector<Eigen::Vector2d>& projected,
                   const std::vector<std::size_t>& use, cv::Size size, int degree) {
  const CentroidBias shape(degree, size, Eigen::MatrixX2d::Zero(CentroidBias::terms(degree), 2));
  // Normal equations, summed point by point: a few well-scaled unknowns (the monomials are
  // normalised to [-1, 1]).
  const int n = CentroidBias::terms(degree);
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  for (const std::size_t i : use) {
    const Eigen::VectorXd m = shape.monomials(centroids[i]);
    const Eigen::Vector2d lean = centroids[i] - projected[i];
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) normal(r, c) += m(r) * m(c);
      rhs(r, 0) += m(r) * lean.x();
      rhs(r, 1) += m(r) * lean.y();
    }
  }
  return {degree, size, normal.ldlt().solve(rhs)};
}

}  // namespace

CentroidBiasFit fit_centroid_bias(const std::vector<Eigen::Vector2d>& centroids,
                                  const std::vector<Eigen::Vector2d>& projected, cv::Size image_size, int degree,
                                  int folds) {
  if (centroids.size() != projected.size()) {
    throw CalibrationError("centroid bias: " + std::to_string(centroids.size()) + " centroids but " +
                           std::to_string(projected.size()) + " projected centres");
  }
  if (degree < 0) throw CalibrationError("centroid bias: degree " + std::to_string(degree) + " is negative");
  const std::size_t needed = 2 * static_cast<std::size_t>(CentroidBias::terms(degree));
  if (centroids.size() < needed) {
    throw CalibrationError("centroid bias: " + std::to_string(centroids.size()) + " points for a field of degree " +
                           std::to_string(degree) + " (needs at least " + std::to_string(needed) + ")");
  }
  std::vector<std::size_t> all(centroids.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  CentroidBiasFit f;
  f.bias = solve(centroids, projected, all, image_size, degree);
  std::vector<Eigen::Vector2d> errors;
  for (std::size_t i = 0; i < all.size(); ++i) errors.emplace_back(f.bias.correct(centroids[i]) - projected[i]);
  f.fit = error_stats(errors);
  // Folds by index modulo k: the plate's objects are in raster order, so each fold spans the image.
  errors.assign(all.size(), Eigen::Vector2d::Zero());
  f.held_out_corrected = centroids;
  const int k = std::max(2, folds);
  for (int fold = 0; fold < k; ++fold) {
    std::vector<std::size_t> train;
    for (const std::size_t i : all) {
      if (static_cast<int>(i % static_cast<std::size_t>(k)) != fold) train.push_back(i);
    }
    if (train.size() < needed / 2) continue;
    const CentroidBias b = solve(centroids, projected, train, image_size, degree);
    for (const std::size_t i : all) {
      if (static_cast<int>(i % static_cast<std::size_t>(k)) == fold) {
        f.held_out_corrected[i] = b.correct(centroids[i]);
        errors[i] = f.held_out_corrected[i] - projected[i];
      }
    }
  }
  f.held_out = error_stats(errors);
  return f;
}

}  // namespace neopipe::calib
