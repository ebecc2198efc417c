#pragma once
// Pixel <-> workspace correspondences from a CSV file with a header naming the columns u,v,X,Y (in
// any order; other columns ignored), one point per line.

#include <string>

#include "calib/correspondence.hpp"

namespace neopipe::calib {

/// Throws CalibrationError naming the file, the line and the cause.
Correspondences read_points_csv(const std::string& path);

}  // namespace neopipe::calib
