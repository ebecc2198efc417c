#pragma once
// `neopipe calibrate`: estimate the global camera's calibration from target images or point pairs,
// report its errors, write it as OpenCV FileStorage YAML; `neopipe calibrate map` maps pixels.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace neopipe::apps {

struct CalibrateArgs {
  std::string target;  ///< dots:COLSxROWS:PITCHmm or chessboard:COLSxROWS:SQUAREmm
  std::vector<std::string> images;
  std::string points;      ///< CSV u,v,X,Y instead of images
  std::string image_size;  ///< with --points
  std::string model = "auto";
  std::string origin;  ///< X,Y[,THETA]: where the target's first point lies on the workspace
  double inlier_mm = 2.0;
  std::string out;
  std::string plot;
  bool quiet = false;
  // calibrate map
  std::string calib;
  std::string map_input;  ///< CSV u,v; empty: stdin
  double height = 0;      ///< mm above the calibrated plane
};

CLI::App* add_calibrate_command(CLI::App& parent, CalibrateArgs& args);
int calibrate_command(const CLI::App& cmd, const CalibrateArgs& args);

}  // namespace neopipe::apps
