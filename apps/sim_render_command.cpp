#include "apps/sim_render_command.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "pipeline/media/media.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/rolling_marbles.hpp"
#include "sim/target_renderer.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

sim::ImageModel image_model(const SimCameraArgs& a) {
  sim::ImageModel m;
  m.noise_sigma = a.noise;
  m.blur_sigma = a.blur;
  m.gradient = a.gradient;
  m.seed = a.seed;
  return m;
}

cv::Size parse_resolution(const std::string& text, const std::string& option = "--resolution", int least = 16) {
  int w = 0;
  int h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !(in >> std::ws).eof() || w < least || h < least || w > 8192 ||
      h > 8192) {
    throw UsageError{fmt::format("{} {}: expected WxH, each {}..8192", option, text, least)};
  }
  return {w, h};
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      return {};
    }
    if (used != item.size() || !std::isfinite(v)) return {};
    out.push_back(v);
  }
  return out;
}

sim::Pose2 parse_pose(const std::string& text, const std::string& where) {
  const auto v = numbers(text);
  if (v.size() != 3) throw UsageError{where + " '" + text + "': expected x,y,theta (mm, mm, degrees)"};
  return {v[0], v[1], v[2] * kDegree};
}

void check_camera_name(const std::string& camera) {
  if (camera != "global" && camera != "onboard") {
    throw UsageError{"--camera " + camera + ": unknown camera (global or onboard)"};
  }
}

void check_on_workspace(const sim::World& w, const sim::Pose2& p, const std::string& what) {
  if (!(p.x >= 0 && p.y >= 0 && p.x <= w.size.x() && p.y <= w.size.y())) {
    throw std::runtime_error(
        fmt::format("{}: ({}, {}) is outside the {} x {} mm workspace", what, p.x, p.y, w.size.x(), w.size.y()));
  }
}

// A path file: header "x,y,theta", then one pose per line (mm, mm, degrees).
std::vector<sim::Pose2> read_path(const std::string& path, const sim::World& world) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ": empty (expected a header x,y,theta)");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != "x,y,theta") throw std::runtime_error(path + ":1: header must be x,y,theta, not '" + line + "'");
  std::vector<sim::Pose2> out;
  for (int n = 2; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto v = numbers(line);
    if (v.size() != 3)
      throw std::runtime_error(fmt::format("{}:{}: expected three numbers x,y,theta, not '{}'", path, n, line));
    out.push_back({v[0], v[1], v[2] * kDegree});
    check_on_workspace(world, out.back(), fmt::format("{}:{}: pose", path, n));
  }
  if (out.empty()) throw std::runtime_error(path + ": no poses after the header");
  return out;
}

std::array<double, 5> parse_distortion(const std::string& text) {
  const auto v = numbers(text);
  if (v.empty() || v.size() > 5)
    throw UsageError{"--distortion '" + text + "': expected up to five numbers k1,k2,p1,p2,k3"};
  std::array<double, 5> d{};
  std::copy(v.begin(), v.end(), d.begin());
  return d;
}

sim::PinholeCamera global_camera(const sim::World& w, const SimCameraArgs& a) {
  sim::GlobalCameraConfig c;
  c.resolution = parse_resolution(a.resolution);
  c.distance = a.distance;
  c.tilt_deg = a.tilt;
  c.tilt_azimuth_deg = a.tilt_azimuth;
  c.roll_deg = a.roll;
  if (!a.distortion.empty()) c.distortion = parse_distortion(a.distortion);
  return sim::make_global_camera(w.size, c);
}

sim::OnboardCameraConfig onboard_config(const SimCameraArgs& a) {
  sim::OnboardCameraConfig c;
  c.window_mm = a.window;
  if (!a.distortion.empty()) c.distortion = parse_distortion(a.distortion);
  return c;
}

void write_truth_header(std::ofstream& out, const std::string& path, bool with_frame) {
  if (!out) throw std::runtime_error(path + ": cannot be written");
  out << (with_frame ? "frame,id,u,v\n" : "id,u,v\n");
}

void write_truth_rows(std::ofstream& out, const std::vector<sim::ProjectedMarble>& rows, std::int64_t frame) {
  for (const auto& r : rows) {
    if (frame >= 0) out << frame << ',';
    out << fmt::format("{},{},{}\n", r.id, r.u, r.v);
  }
}

void write_camera(const sim::PinholeCamera& camera, const std::string& path) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  if (!fs.isOpened()) throw std::runtime_error(path + ": cannot be written");
  fs << "image_width" << camera.size().width << "image_height" << camera.size().height;
  fs << "camera_matrix" << camera.camera_matrix() << "distortion_coefficients" << camera.distortion_coefficients();
  cv::Mat r(3, 3, CV_64F);
  cv::Mat t(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.at<double>(i, j) = camera.rotation()(i, j);
    t.at<double>(i) = camera.translation()(i);
  }
  fs << "world_to_camera_rotation" << r << "world_to_camera_translation" << t;
  // The plane z = 0 seen through the lens-free camera: world (X, Y, 1) ~ H (u, v, 1) for undistorted
  // pixels, H = (K [r1 r2 t])^-1 scaled so H(2,2) = 1.
  cv::Mat krt = camera.camera_matrix() * (cv::Mat_<double>(3, 3) << r.at<double>(0, 0), r.at<double>(0, 1),
                                          t.at<double>(0), r.at<double>(1, 0), r.at<double>(1, 1), t.at<double>(1),
                                          r.at<double>(2, 0), r.at<double>(2, 1), t.at<double>(2));
  cv::Mat h = krt.inv();
  h /= h.at<double>(2, 2);
  fs << "undistorted_image_to_world" << h;
}

void write_image(const std::string& path, const cv::Mat& image) {
  if (!pipeline::media::write_image(path, image))
    throw std::runtime_error(path + ": cannot write an image there (use .png, .jpg, .tif or .bmp)");
}

std::pair<sim::CalibrationTarget, sim::TargetPose> parse_target(const SimRenderArgs& a) {
  sim::CalibrationTarget t;
  t.kind = a.target == "dots" ? sim::TargetKind::dots : sim::TargetKind::chessboard;
  // --target-grid counts dots, or a chessboard's inner corners (OpenCV's pattern size); the board
  // has one square more each way.
  cv::Size g = t.kind == sim::TargetKind::dots ? cv::Size(11, 8) : cv::Size(9, 6);
  if (!a.target_grid.empty()) g = parse_resolution(a.target_grid, "--target-grid", 2);
  const int squares = t.kind == sim::TargetKind::dots ? 0 : 1;
  t.cols = g.width + squares;
  t.rows = g.height + squares;
  t.pitch = a.pitch;
  t.dot_diameter = a.dot_diameter;
  if (t.kind == sim::TargetKind::dots && !(t.dot_diameter < t.pitch)) {
    throw UsageError{"--dot-diameter must be smaller than --pitch, or the dots touch"};
  }
  std::vector<double> p{40, 40, 0, 0, 0, 0};
  if (!a.target_pose.empty()) {
    const auto v = numbers(a.target_pose);
    if (v.size() != 4 && v.size() != 6) {
      throw UsageError{"--target-pose '" + a.target_pose + "': expected x,y,z,theta or x,y,z,theta,tilt_x,tilt_y"};
    }
    std::copy(v.begin(), v.end(), p.begin());
  }
  return {t, sim::target_pose(p[0], p[1], p[2], p[3], p[4], p[5])};
}

}  // namespace

void add_sim_camera_options(CLI::App& cmd, SimCameraArgs& a) {
  cmd.add_option("--world", a.world, "World file (YAML), e.g. from neopipe sim world")->required()->type_name("W.yaml");
  cmd.add_option("--camera", a.camera, "Which camera: global (above the workspace) or onboard (on the arm)")
      ->type_name("global|onboard")
      ->capture_default_str();
  cmd.add_option("--resolution", a.resolution, "Global camera image size")->type_name("WxH")->capture_default_str();
  cmd.add_option("--distance", a.distance, "Global camera: distance from the workspace centre, mm")
      ->check(CLI::Range(10.0, 1e6))
      ->capture_default_str();
  cmd.add_option("--tilt", a.tilt, "Global camera: optical axis from vertical, degrees")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  cmd.add_option("--tilt-azimuth", a.tilt_azimuth, "Global camera: direction it leans towards, degrees from East")
      ->capture_default_str();
  cmd.add_option("--roll", a.roll, "Global camera: turn about the optical axis, degrees")->capture_default_str();
  cmd.add_option("--distortion", a.distortion, "Lens k1,k2,p1,p2,k3 (OpenCV's model; default: the camera's own)")
      ->type_name("K1,K2,P1,P2,K3");
  cmd.add_option("--window", a.window, "Onboard camera: view window side a, mm")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  cmd.add_option("--noise", a.noise, "Sensor noise sigma, gray levels (0: off)")
      ->check(CLI::Range(0.0, 64.0))
      ->capture_default_str();
  cmd.add_option("--blur", a.blur, "Optical blur sigma, pixels (0: off)")
      ->check(CLI::Range(0.0, 8.0))
      ->capture_default_str();
  cmd.add_option("--gradient", a.gradient, "Illumination gradient, +- fraction across the image (0: off)")
      ->check(CLI::Range(0.0, 0.9))
      ->capture_default_str();
  cmd.add_option("--seed", a.seed, "Noise seed: same seed, same pixels")->capture_default_str();
}

int sim_render_command(const SimRenderArgs& a) {
  check_camera_name(a.cam.camera);
  const sim::World world = sim::load_world(a.cam.world);
  std::optional<sim::PinholeCamera> camera;
  if (a.cam.camera == "global") {
    if (!a.pose.empty()) throw UsageError{"--pose is for the onboard camera; the global camera stays put"};
    camera = global_camera(world, a.cam);
  } else {
    const sim::Pose2 pose =
        a.pose.empty() ? sim::Pose2{world.size.x() / 2, world.size.y() / 2, 0} : parse_pose(a.pose, "--pose");
    check_on_workspace(world, pose, "--pose " + a.pose);
    camera = sim::make_onboard_camera(pose, onboard_config(a.cam));
  }
  const sim::MarbleRenderer renderer(image_model(a.cam), camera->size());
  cv::Mat frame;
  std::vector<sim::ProjectedMarble> truth;
  if (a.target.empty()) {
    frame = renderer.render(world.objects, world.marble_diameter, *camera, 0);
    truth = sim::visible_marbles(world.objects, *camera);
  } else {
    const auto [target, pose] = parse_target(a);
    frame = sim::render_target(target, pose, *camera, renderer);
    const auto points = sim::projected_target_points(target, pose, *camera);
    for (std::size_t i = 0; i < points.size(); ++i)
      truth.push_back({static_cast<int>(i), points[i].x(), points[i].y()});
  }
  write_image(a.cam.out, frame);
  if (!a.cam.truth.empty()) {
    std::ofstream out(a.cam.truth);
    write_truth_header(out, a.cam.truth, false);
    write_truth_rows(out, truth, -1);
  }
  if (!a.camera_out.empty()) write_camera(*camera, a.camera_out);
  std::cerr << fmt::format("neopipe sim render: {} camera, {}x{}, {} -> {}\n", a.cam.camera, frame.cols, frame.rows,
                           a.target.empty()
                               ? fmt::format("{} of {} marbles in view", truth.size(), world.objects.size())
                               : fmt::format("{} target, {} points", a.target, truth.size()),
                           a.cam.out);
  return kExitOk;
}

int sim_video_command(const SimVideoArgs& a) {
  check_camera_name(a.cam.camera);
  const sim::World world = sim::load_world(a.cam.world);
  const bool onboard = a.cam.camera == "onboard";
  std::vector<sim::Pose2> poses;
  if (onboard) {
    if (a.path.empty()) throw UsageError{"the onboard camera needs --path (CSV x,y,theta)"};
    const auto keys = read_path(a.path, world);
    // --steps frames from each pose to the next, straight lines and turns interpolated.
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      for (int s = 0; s < a.steps; ++s) {
        const double t = static_cast<double>(s) / a.steps;
        poses.push_back({keys[i].x + t * (keys[i + 1].x - keys[i].x), keys[i].y + t * (keys[i + 1].y - keys[i].y),
                         keys[i].theta + t * (keys[i + 1].theta - keys[i].theta)});
      }
    }
    poses.push_back(keys.back());
  } else if (!a.path.empty()) {
    throw UsageError{"--path is for the onboard camera; the global camera films moving marbles (--frames, --speed)"};
  }
  const auto frames = onboard ? static_cast<std::int64_t>(poses.size()) : std::int64_t{a.frames};
  const sim::PinholeCamera fixed =
      onboard ? sim::make_onboard_camera(poses.front(), onboard_config(a.cam)) : global_camera(world, a.cam);
  const sim::MarbleRenderer renderer(image_model(a.cam), fixed.size());

  sim::RollingMarbles rolling(world, onboard ? 0.0 : a.speed, a.cam.seed);

  const auto writer = pipeline::media::open_video_writer(a.cam.out, a.fps, fixed.size());
  if (!writer) {
    throw std::runtime_error(a.cam.out + ": cannot write a video there (use .mp4, .avi or .mkv)");
  }
  std::ofstream truth;
  if (!a.cam.truth.empty()) {
    truth.open(a.cam.truth);
    write_truth_header(truth, a.cam.truth, true);
  }
  ProgressBar bar("neopipe sim video", frames, !a.quiet);
  cv::Mat bgr;
  for (std::int64_t f = 0; f < frames; ++f) {
    const sim::PinholeCamera camera =
        onboard ? sim::make_onboard_camera(poses[static_cast<std::size_t>(f)], onboard_config(a.cam)) : fixed;
    const auto& marbles = rolling.positions();
    const cv::Mat frame = renderer.render(marbles, world.marble_diameter, camera, f);
    cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
    writer->write(bgr);
    if (truth.is_open()) write_truth_rows(truth, sim::visible_marbles(marbles, camera), f);
    rolling.step(1 / a.fps);
    bar.update(f + 1);
  }
  bar.clear();
  std::cerr << fmt::format("neopipe sim video: {} camera, {} frames of {}x{} -> {}\n", a.cam.camera, frames,
                           fixed.size().width, fixed.size().height, a.cam.out);
  return kExitOk;
}

}  // namespace neopipe::apps
