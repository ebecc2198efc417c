#pragma once
// A picture of a calibration's errors: each target point at its workspace position, an arrow from
// it along its error, magnified by a round factor so the pattern shows (radial for an unmodelled
// lens, a swirl for a turned plane, noise for a good fit).

#include <string>
#include <vector>

#include "calib/correspondence.hpp"

namespace neopipe::calib {

/// Writes a PNG to `path`; `errors[i]` is mapped minus true for `points[i]` (mm). Throws
/// CalibrationError if the file cannot be written.
void write_residual_plot(const Correspondences& points, const std::vector<Eigen::Vector2d>& errors,
                         const std::string& title, const std::string& path);

}  // namespace neopipe::calib
