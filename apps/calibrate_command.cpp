#include "apps/calibrate_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "calib/calibration.hpp"
#include "calib/estimate.hpp"
#include "calib/image_calibration.hpp"
#include "calib/plane_pose.hpp"
#include "calib/points_csv.hpp"
#include "calib/residual_plot.hpp"

namespace neopipe::apps {
namespace {

std::vector<double> parse_origin(const std::string& text) {
  std::vector<double> v;
  bool ok = true;
  std::stringstream in(text);
  std::string item;
  while (ok && std::getline(in, item, ',')) {
    std::size_t used = 0;
    try {
      v.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    ok = used > 0 && used == item.size() && std::isfinite(v.back());
  }
  if (ok && v.size() == 2) v.push_back(0);
  if (!ok || v.size() != 3)
    throw UsageError{"--target-origin " + text + ": expected X,Y or X,Y,THETA (mm, mm, degrees)"};
  return v;
}

void print_stats(const std::string& label, const calib::ErrorStats& s) {
  std::cerr << fmt::format(
      "  {:<9} mean ({:+.4f}, {:+.4f}) mm, sd ({:.4f}, {:.4f}) mm, RMS {:.4f} mm, max {:.4f} mm, "
      "{} points\n",
      label, s.mean.x(), s.mean.y(), s.sd.x(), s.sd.y(), s.rms, s.max, s.points);
}

void print_report(const calib::Calibration& c, const std::string& out) {
  const auto& r = c.report;
  std::cerr << fmt::format("neopipe calibrate: model {}, {} view(s) used, {} rejected; {} points used, {} rejected\n",
                           calib::model_name(c.model), r.views_used, r.views_rejected, r.points_used,
                           r.points_rejected);
  for (const auto& why : r.rejected) std::cerr << "  rejected: " << why << '\n';
  print_stats("fit", r.fit);
  print_stats("held out", r.held_out);
  std::cerr << fmt::format("  reprojection RMS {:.4f} px\n", r.reprojection_rms_px);
  if (r.homography_held_out_rms >= 0 && r.full_held_out_rms >= 0) {
    std::cerr << fmt::format("  held-out RMS: homography {:.4f} mm, full {:.4f} mm: the {} model fits better\n",
                             r.homography_held_out_rms, r.full_held_out_rms,
                             r.full_held_out_rms < r.homography_held_out_rms ? "full" : "homography");
  }
  std::cerr << "  -> " << out << '\n';
}

void plot_residuals(const calib::Calibration& c, const calib::Correspondences& points, const std::string& title,
                    const std::string& path) {
  std::vector<Eigen::Vector2d> pixels;
  pixels.reserve(points.size());
  for (const auto& p : points) pixels.push_back(p.pixel);
  const auto mapped = c.to_world(pixels);
  std::vector<Eigen::Vector2d> errors;
  errors.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) errors.emplace_back(mapped[i] - points[i].world);
  calib::write_residual_plot(points, errors, title, path);
}

calib::Calibration from_images(const CalibrateArgs& a) {
  calib::ImageCalibrationOptions o;
  try {
    o.target = calib::parse_target(a.target);
  } catch (const std::invalid_argument& e) {
    throw UsageError{e.what()};
  }
  if (!a.origin.empty()) {
    const auto origin = parse_origin(a.origin);
    o.origin = {origin[0], origin[1], origin[2]};
  }
  o.model = a.model;
  o.inlier_mm = a.inlier_mm;
  ProgressBar bar("neopipe calibrate", static_cast<std::int64_t>(a.images.size()), !a.quiet);
  o.progress = [&](std::size_t done) { bar.update(static_cast<std::int64_t>(done)); };
  calib::ImageCalibration result = calib::calibrate_images(a.images, o);
  bar.clear();
  calib::Calibration& c = result.calibration;
  if (!a.plot.empty()) {
    plot_residuals(c, result.workspace,
                   fmt::format("{} model, {} ({})", calib::model_name(c.model), a.images[0], a.target), a.plot);
  }
  return c;
}

calib::Calibration from_points(const CalibrateArgs& a) {
  if (a.model == "full") throw UsageError{"--points gives one plane's pairs: only the homography model fits them"};
  const calib::Correspondences points = calib::read_points_csv(a.points);
  // The pairs do not say which image size they came from: 0 x 0 (unknown) unless --image-size says.
  cv::Size size(0, 0);
  if (!a.image_size.empty()) {
    int w = 0;
    int h = 0;
    char x = 0;
    std::istringstream in(a.image_size);
    if (!(in >> w >> x >> h) || x != 'x' || !(in >> std::ws).eof() || w <= 0 || h <= 0) {
      throw UsageError{"--image-size " + a.image_size + ": expected WxH pixels"};
    }
    size = {w, h};
  }
  calib::EstimateOptions o;
  o.ransac.inlier_mm = a.inlier_mm;
  calib::Calibration c = calib::calibrate_homography(points, size, o);
  if (!a.plot.empty()) plot_residuals(c, points, "homography model, " + a.points, a.plot);
  return c;
}

int map_command(const CalibrateArgs& a) {
  const calib::Calibration c = calib::load_calibration(a.calib);
  std::ifstream file;
  if (!a.map_input.empty()) {
    file.open(a.map_input);
    if (!file) throw calib::CalibrationError(a.map_input + ": cannot be read");
  }
  std::istream& in = a.map_input.empty() ? std::cin : file;
  const std::string name = a.map_input.empty() ? "<stdin>" : a.map_input;
  std::string line;
  if (!std::getline(in, line)) throw calib::CalibrationError(name + ": empty (expected a header u,v)");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != "u,v") throw calib::CalibrationError(name + ":1: header must be u,v, not '" + line + "'");
  std::cout << "u,v,X,Y\n";
  for (int n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    double u = 0;
    double v = 0;
    char comma = 0;
    std::istringstream row(line);
    if (!(row >> u >> comma >> v) || comma != ',' || !(row >> std::ws).eof() || !std::isfinite(u) ||
        !std::isfinite(v)) {
      throw calib::CalibrationError(fmt::format("{}:{}: expected two numbers u,v, not '{}'", name, n, line));
    }
    const Eigen::Vector2d w = calib::to_world_at_height(c, {{u, v}}, a.height).front();
    std::cout << fmt::format("{},{},{},{}\n", u, v, w.x(), w.y());
  }
  std::cout.flush();
  return kExitOk;
}

}  // namespace

CLI::App* add_calibrate_command(CLI::App& parent, CalibrateArgs& a) {
  CLI::App* cmd = parent.add_subcommand(
      "calibrate", "Calibrate the global camera: image -> workspace mapping with an error report (OpenCV YAML)");
  cmd->add_option("images", a.images,
                  "Target images; the FIRST shows the target lying on the workspace at --target-origin, the others "
                  "anywhere (for the lens)")
      ->type_name("IMAGE...");
  cmd->add_option("--target", a.target,
                  "dots:COLSxROWS:PITCHmm (bright dots) or chessboard:COLSxROWS:SQUAREmm (inner corners)")
      ->type_name("KIND:CxR:PITCH");
  cmd->add_option("--points", a.points, "CSV with columns u,v,X,Y (pixel, workspace mm) instead of images")
      ->check(CLI::ExistingFile)
      ->type_name("pairs.csv");
  cmd->add_option("--image-size", a.image_size, "With --points: the image size they come from (recorded in the file)")
      ->type_name("WxH");
  cmd->add_option("--model", a.model, "homography (the paper's A), full (lens + plane), or auto (full from 3 views)")
      ->check(CLI::IsMember({"auto", "homography", "full"}))
      ->capture_default_str();
  cmd->add_option("--target-origin", a.origin,
                  "Where the first image's first dot/corner lies on the workspace, and its rows' direction from East")
      ->type_name("X,Y[,THETA]");
  cmd->add_option("--inlier-mm", a.inlier_mm, "RANSAC: a point further than this from the fit is an outlier")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--out", a.out, "Calibration file to write (OpenCV FileStorage YAML)")->type_name("calib.yaml");
  cmd->add_option("--plot", a.plot, "Residual plot: error arrows over the target (PNG)")->type_name("residuals.png");
  cmd->add_flag("-q,--quiet", a.quiet, "No progress bar");
  cmd->footer(
      "Targets: dots are numbered along rows from the one seen bottom-left when the target lies upright; a "
      "chessboard's\n"
      "COLSxROWS are its inner corners (OpenCV's pattern size). Map pixels with: neopipe calibrate map --calib FILE.");
  cmd->require_subcommand(0, 1);
  CLI::App* map = cmd->add_subcommand("map", "Map pixels (CSV u,v on stdin or a file) to workspace X,Y (mm)");
  map->add_option("--calib", a.calib, "Calibration file")->required()->type_name("calib.yaml");
  map->add_option("input", a.map_input, "CSV with header u,v (default: stdin)")->type_name("FILE");
  map->add_option("--height", a.height,
                  "The points lie this far above the calibrated plane, mm (a marble's centre: its radius, less the "
                  "board's thickness); needs the full model")
      ->capture_default_str();
  return cmd;
}

int calibrate_command(const CLI::App& cmd, const CalibrateArgs& a) {
  if (cmd.got_subcommand("map")) return map_command(a);
  if (a.out.empty()) throw UsageError{"--out is required (the calibration file to write)"};
  if (a.points.empty() == a.target.empty()) throw UsageError{"give either --target with images, or --points"};
  if (!a.target.empty() && a.images.empty()) throw UsageError{"--target needs images of the target"};
  if (!a.points.empty() && !a.images.empty()) throw UsageError{"--points takes no images"};
  const calib::Calibration c = a.points.empty() ? from_images(a) : from_points(a);
  calib::save_calibration(c, a.out);
  print_report(c, a.out);
  return kExitOk;
}

}  // namespace neopipe::apps
