#pragma once
// How far a blob's centroid lies from where the object's centre projects, as a smooth field over the
// image: the bias a calibration measures on objects at known places and the survey removes.
//
// Why: a lit marble's intensity-weighted centroid leans towards the lamp by a third of a pixel on the
// global camera (shading, highlight, shadow; docs/calibration.md), far more than the 0.05 mm the
// survey may miss by. The lean depends on where the marble is under the lamp and how defocused the
// lens is there, both smooth across the image, so a low-order polynomial in the pixel position
// captures it: after it, the weighted centroid misses by 0.02 px, about its noise.

#include <Eigen/Core>
#include <opencv2/core/types.hpp>
#include <vector>

#include "calib/calibration.hpp"

namespace neopipe::calib {

class CentroidBias {
 public:
  CentroidBias() = default;
  /// A field of total degree `degree` (0: a constant) over images of `size`, with `coefficients`
  /// (one row per monomial, in the order of monomials(); columns: u and v).
  CentroidBias(int degree, cv::Size size, Eigen::MatrixX2d coefficients);

  /// The bias (px) at pixel `p`: centroid minus projected centre.
  [[nodiscard]] Eigen::Vector2d at(const Eigen::Vector2d& p) const;
  /// The centre's projection from a measured centroid: p - at(p).
  [[nodiscard]] Eigen::Vector2d correct(const Eigen::Vector2d& p) const { return p - at(p); }

  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] cv::Size image_size() const { return size_; }
  [[nodiscard]] const Eigen::MatrixX2d& coefficients() const { return coefficients_; }
  [[nodiscard]] bool empty() const { return coefficients_.rows() == 0; }

  /// The number of monomials of total degree <= d in two variables.
  static int terms(int degree) { return (degree + 1) * (degree + 2) / 2; }
  /// The monomials at `p`, normalised to [-1, 1] over the image, in a fixed order.
  [[nodiscard]] Eigen::VectorXd monomials(const Eigen::Vector2d& p) const;

 private:
  int degree_ = 0;
  cv::Size size_;
  Eigen::MatrixX2d coefficients_;
};

struct CentroidBiasFit {
  CentroidBias bias;
  ErrorStats fit;       ///< px: corrected centroids against the projected centres they were fitted to
  ErrorStats held_out;  ///< px: each point corrected by a field fitted without its fold (k-fold)
  /// Each centroid corrected by the field fitted without its fold: what the centre's projection
  /// would be estimated as had that object not been used (for errors further down the chain).
  std::vector<Eigen::Vector2d> held_out_corrected;
};

/// Fits the field of total degree `degree` to `centroids` measured where objects' centres project to
/// `projected` (px). Throws CalibrationError for mismatched lists or fewer points than twice the
/// field's terms.
CentroidBiasFit fit_centroid_bias(const std::vector<Eigen::Vector2d>& centroids,
                                  const std::vector<Eigen::Vector2d>& projected, cv::Size image_size, int degree = 2,
                                  int folds = 5);

}  // namespace neopipe::calib
