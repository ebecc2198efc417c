#pragma once
// A calibration's raw material: where a point of the workspace (or of a target) was seen in the
// image.

#include <Eigen/Core>
#include <stdexcept>
#include <vector>

namespace neopipe::calib {

/// Bad calibration input or an impossible fit; the message names the input and the cause in one line.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Correspondence {
  Eigen::Vector2d pixel;  ///< image position, px (OpenCV convention: (0,0) is the top-left pixel's centre)
  Eigen::Vector2d world;  ///< plane position, mm (workspace, or the target's own plane)
};

using Correspondences = std::vector<Correspondence>;

}  // namespace neopipe::calib
