#pragma once
// The centre of a lit marble from a model of its image, not from its pixels' mass. A sphere under a
// lamp is not symmetric about its centre in the image: one side is shaded, the rim facing the lamp
// is brighter than the far rim, a highlight sits towards the lamp and the marble's shadow darkens
// the table on the far side. Blur spreads a bright edge further than a dim one past any fixed
// threshold, so binary and intensity-weighted centroids lean towards the lamp by tenths of a pixel.
//
// The model: a disk of radius R at c shaded as a Lambertian sphere under a distant light (a plane in
// the position plus a dome), on a flat table darkened by a disk-shaped shadow displaced from the
// marble, all blurred by a Gaussian of width sigma; fitted by Levenberg-Marquardt to the pixels
// around the blob, but for its middle, where the highlight is; a soft prior holds the radius near
// the expected one.
//
// Measured on the rig's global camera (bench/survey_centroids.cpp, docs/calibration.md): nearly
// unbiased (0.005 px mean) but scattered (0.11 px RMS: some fits settle on the wrong shadow) and
// slow (0.19 s a marble). The survey uses the weighted centroid corrected for its measured lean
// instead (0.02 px RMS); this fit is the third candidate it was measured against. The edge's position is set by the
// edge pixels, where the blurred step lies, whatever the levels on either side, so shading, highlight and shadow no
// longer pull the centre.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <optional>

namespace neopipe::calib {

struct MarbleFitOptions {
  double patch = 1.9;       ///< pixels within this many expected radii of the seed are fitted ...
  double hole = 0.55;       ///< ... but for those within this many (the highlight's)
  bool shadow = true;       ///< model a shadow beside the marble (a second, dark, displaced disk)
  int max_iterations = 40;  ///< per stage
  /// Gray levels of residual per pixel the radius strays from the expected one: a soft prior.
  double radius_weight = 10;
};

struct MarbleFit {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< px, pixel centres at integer coordinates
  double radius = 0;                                 ///< px, of the silhouette
  double blur = 0;                                   ///< px, the fitted Gaussian's sigma
  double rms = 0;                                    ///< gray levels, residual of the fit
  int pixels = 0;                                    ///< fitted
};

/// Fits the marble whose image is near `seed` (px) with a silhouette of about `radius` px in a
/// CV_8UC1 image. None when the patch leaves the image or the fit does not find a marble there
/// (no edge, a radius far from the expected one).
std::optional<MarbleFit> fit_marble(const cv::Mat& gray, const Eigen::Vector2d& seed, double radius,
                                    const MarbleFitOptions& options = {});

}  // namespace neopipe::calib
