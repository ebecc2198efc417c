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
#include "sim/jpeg_loss.hpp"
#include "sim/marble_truth.hpp"
#include "sim/rolling_marbles.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/target_renderer.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

constexpr double kRenderDegree = std::numbers::pi / 180;

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
  return {v[0], v[1], v[2] * kRenderDegree};
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
    out.push_back({v[0], v[1], v[2] * kRenderDegree});
    check_on_workspace(world, out.back(), fmt::format("{}:{}: pose", path, n));
  }
  if (out.empty()) throw std::runtime_error(path + ": no poses after the header");
  return out;
}

std::array<double, 5> parse_five(const std::string& text, const std::string& option, const std::string& names) {
  const auto v = numbers(text);
  if (v.empty() || v.size() > 5) throw UsageError{option + " '" + text + "': expected up to five numbers " + names};
  std::array<double, 5> d{};
  std::copy(v.begin(), v.end(), d.begin());
  return d;
}

sim::PinholeCamera global_camera(const sim::World& w, const SimCameraArgs& a, const sim::Rendering& r) {
  sim::GlobalCameraConfig c;
  c.resolution = parse_resolution(a.resolution);
  c.distance = a.distance;
  c.tilt_deg = a.tilt;
  c.tilt_azimuth_deg = a.tilt_azimuth;
  c.roll_deg = a.roll;
  return sim::make_global_camera(w.size, c, r);
}

sim::OnboardCameraConfig onboard_config(const SimCameraArgs& a, const sim::Rendering& r, double diameter) {
  sim::OnboardCameraConfig c;
  c.window_mm = a.window;
  return sim::onboard_config_for(r, diameter, c);
}

void write_truth_header(std::ofstream& out, const std::string& path, bool with_frame) {
  if (!out) throw std::runtime_error(path + ": cannot be written");
  out << (with_frame ? "frame,id,u,v,u0,v0\n" : "id,u,v,u0,v0\n");
}

void write_truth_rows(std::ofstream& out, const std::vector<sim::MarbleTruth>& rows, std::int64_t frame) {
  for (const auto& r : rows) {
    if (frame >= 0) out << frame << ',';
    out << fmt::format("{},{},{},{},{}\n", r.id, r.u, r.v, r.u0, r.v0);
  }
}

// The option a Rendering field is set by, for validate()'s messages.
std::string option_for(const std::string& message) {
  static const std::pair<const char*, const char*> kFields[] = {
      {"light.position", "--light"},       {"light.ambient", "--ambient"},    {"light.specular", "--specular"},
      {"light.shininess", "--shininess"},  {"surfaces.texture", "--texture"}, {"lens.k", "--distortion/--lens-extra"},
      {"lens.p", "--distortion"},          {"lens.s", "--lens-extra"},        {"lens:", "--distortion/--lens-extra:"},
      {"defocus.centre", "--blur"},        {"defocus.corner", "--defocus"},   {"sensor.read_noise", "--noise"},
      {"sensor.full_well", "--full-well"}, {"sensor.prnu", "--prnu"},         {"sensor.vignetting", "--vignetting"},
      {"sensor.gradient", "--gradient"}};
  for (const auto& [field, option] : kFields) {
    if (message.rfind(field, 0) == 0) return std::string(option) + " (" + message + ")";
  }
  return message;
}

void write_camera(const sim::PinholeCamera& camera, const std::string& path) {
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  if (!fs.isOpened()) throw std::runtime_error(path + ": cannot be written");
  fs << "image_width" << camera.size().width << "image_height" << camera.size().height;
  fs << "camera_matrix" << camera.camera_matrix() << "distortion_coefficients" << camera.distortion_coefficients();
  // Beyond OpenCV's five terms (sim/lens.hpp): what a five-term calibration cannot fit.
  fs << "extra_distortion_model"
     << "x' += x k4 r^8 + s1 r^2 + s2 r^4; y' += y k4 r^8 + s3 r^2 + s4 r^4";
  fs << "extra_distortion_coefficients" << camera.extra_distortion_coefficients();
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

sim::Rendering rendering_of(const SimCameraArgs& a, sim::CameraKind kind, const Eigen::Vector2d& workspace) {
  sim::Rendering r = sim::rendering_for(sim::parse_realism(a.realism), kind, workspace);
  if (a.no_light && !a.light.empty()) throw UsageError{"--light and --no-light: choose one"};
  if (a.interlace && a.no_interlace) throw UsageError{"--interlace and --no-interlace: choose one"};
  if (a.no_light) r.light.reset();
  if (!a.light.empty()) {
    const auto v = numbers(a.light);
    if (v.size() != 3) throw UsageError{"--light '" + a.light + "': expected x,y,z (mm)"};
    if (!r.light) r.light = sim::PointLight{};
    r.light->position = {v[0], v[1], v[2]};
  }
  const bool light_option = a.ambient || a.specular || a.shininess || a.no_shadows;
  if (light_option && !r.light) {
    throw UsageError{"--ambient, --specular, --shininess and --no-shadows need a light (give --light X,Y,Z)"};
  }
  if (a.ambient) r.light->ambient = *a.ambient;
  if (a.specular) r.light->specular = *a.specular;
  if (a.shininess) r.light->shininess = *a.shininess;
  if (a.no_shadows) r.light->shadows = false;
  if (a.texture) r.surfaces.texture = *a.texture;
  if (!a.distortion.empty()) r.lens.opencv = parse_five(a.distortion, "--distortion", "k1,k2,p1,p2,k3");
  if (!a.lens_extra.empty()) {
    r.lens.extra = sim::LensExtras::from_array(parse_five(a.lens_extra, "--lens-extra", "k4,s1,s2,s3,s4"));
  }
  if (a.vignetting) r.sensor.vignetting = *a.vignetting;
  if (a.blur) {
    // A uniform blur (the preset's centre and corner alike) stays uniform; else --blur is the centre's.
    if (r.defocus.corner == r.defocus.centre) r.defocus.corner = *a.blur;
    r.defocus.centre = *a.blur;
  }
  if (a.defocus) r.defocus.corner = *a.defocus;
  if (a.noise) r.sensor.read_noise = *a.noise;
  if (a.full_well) r.sensor.full_well = *a.full_well;
  if (a.no_shot_noise) r.sensor.full_well.reset();
  if (a.prnu) r.sensor.prnu = *a.prnu;
  if (a.gradient) r.sensor.gradient = *a.gradient;
  if (a.interlace) r.interlace = true;
  if (a.no_interlace) r.interlace = false;
  r.sensor.seed = a.seed;
  try {
    r.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError{option_for(e.what())};
  }
  return r;
}

int sim_render_command(const SimRenderArgs& a) {
  check_camera_name(a.cam.camera);
  const sim::World world = sim::load_world(a.cam.world);
  const bool global = a.cam.camera == "global";
  const sim::Rendering rendering =
      rendering_of(a.cam, global ? sim::CameraKind::global : sim::CameraKind::onboard, world.size);
  std::optional<sim::PinholeCamera> camera;
  if (global) {
    if (!a.pose.empty()) throw UsageError{"--pose is for the onboard camera; the global camera stays put"};
    camera = global_camera(world, a.cam, rendering);
  } else {
    const sim::Pose2 pose =
        a.pose.empty() ? sim::Pose2{world.size.x() / 2, world.size.y() / 2, 0} : parse_pose(a.pose, "--pose");
    check_on_workspace(world, pose, "--pose " + a.pose);
    camera = sim::make_onboard_camera(pose, onboard_config(a.cam, rendering, world.marble_diameter), rendering);
  }
  const sim::SceneRenderer renderer(rendering, *camera);
  cv::Mat frame;
  std::vector<sim::MarbleTruth> truth;
  if (a.target.empty()) {
    frame = renderer.render(world.objects, world.marble_diameter, *camera, 0);
    truth = sim::marble_truth(world.objects, world.marble_diameter, *camera, rendering.shape);
  } else {
    const auto [target, pose] = parse_target(a);
    frame = sim::render_target(target, pose, *camera, renderer);
    const auto points = sim::projected_target_points(target, pose, *camera);
    for (std::size_t i = 0; i < points.size(); ++i) {
      truth.push_back({static_cast<int>(i), points[i].x(), points[i].y(), points[i].x(), points[i].y()});
    }
  }
  write_image(a.cam.out, frame);
  if (!a.cam.truth.empty()) {
    std::ofstream out(a.cam.truth);
    if (a.target.empty()) {
      write_truth_header(out, a.cam.truth, false);
      write_truth_rows(out, truth, -1);
    } else {
      if (!out) throw std::runtime_error(a.cam.truth + ": cannot be written");
      out << "id,u,v\n";  // points of the target's plane: no parallax to tell apart
      for (const auto& t : truth) out << fmt::format("{},{},{}\n", t.id, t.u, t.v);
    }
  }
  if (!a.camera_out.empty()) write_camera(*camera, a.camera_out);
  std::cerr << fmt::format("neopipe sim render: {} camera, {} realism, {}x{}, {} -> {}\n", a.cam.camera, a.cam.realism,
                           frame.cols, frame.rows,
                           a.target.empty()
                               ? fmt::format("{} of {} marbles in view", truth.size(), world.objects.size())
                               : fmt::format("{} target, {} points", a.target, truth.size()),
                           a.cam.out);
  return kExitOk;
}

namespace {

// The lossy step each preset's recorder applies to a frame: none, or JPEG at a quality.
struct Compression {
  std::string codec;
  int quality = 0;
};

Compression compression_of(const SimVideoArgs& a) {
  const sim::Realism realism = sim::parse_realism(a.cam.realism);
  Compression c{realism == sim::Realism::ideal ? "none" : "jpeg", realism == sim::Realism::harsh ? 50 : 90};
  if (!a.codec.empty()) c.codec = a.codec;
  if (a.quality) {
    if (c.codec != "jpeg") throw UsageError{"--quality is for --codec jpeg"};
    c.quality = *a.quality;
  }
  return c;
}

}  // namespace

int sim_video_command(const SimVideoArgs& a) {
  check_camera_name(a.cam.camera);
  const sim::World world = sim::load_world(a.cam.world);
  const bool onboard = a.cam.camera == "onboard";
  const sim::Rendering rendering =
      rendering_of(a.cam, onboard ? sim::CameraKind::onboard : sim::CameraKind::global, world.size);
  const Compression compression = compression_of(a);
  std::vector<sim::Pose2> poses;
  if (onboard) {
    if (a.path.empty()) throw UsageError{"the onboard camera needs --path (CSV x,y,theta)"};
    const auto keys = read_path(a.path, world);
    // --steps frames from each pose to the next, straight lines and turns interpolated; twice as
    // many instants for the odd fields of interlaced frames.
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      for (int s = 0; s < 2 * a.steps; ++s) {
        const double t = static_cast<double>(s) / (2 * a.steps);
        poses.push_back({keys[i].x + t * (keys[i + 1].x - keys[i].x), keys[i].y + t * (keys[i + 1].y - keys[i].y),
                         keys[i].theta + t * (keys[i + 1].theta - keys[i].theta)});
      }
    }
    poses.push_back(keys.back());
    poses.push_back(keys.back());
  } else if (!a.path.empty()) {
    throw UsageError{"--path is for the onboard camera; the global camera films moving marbles (--frames, --speed)"};
  }
  const auto frames = onboard ? static_cast<std::int64_t>(poses.size() / 2) : std::int64_t{a.frames};
  const sim::OnboardCameraConfig onboard_camera = onboard_config(a.cam, rendering, world.marble_diameter);
  const sim::Intrinsics onboard_k = sim::onboard_intrinsics(onboard_camera, rendering);
  const sim::PinholeCamera fixed = onboard ? sim::onboard_camera_at(poses.front(), onboard_camera, onboard_k)
                                           : global_camera(world, a.cam, rendering);
  const sim::SceneRenderer renderer(rendering, fixed);

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
    const auto at = static_cast<std::size_t>(2 * f);
    const sim::PinholeCamera camera = onboard ? sim::onboard_camera_at(poses[at], onboard_camera, onboard_k) : fixed;
    const sim::PinholeCamera odd_camera =
        onboard ? sim::onboard_camera_at(poses[at + 1], onboard_camera, onboard_k) : fixed;
    const std::vector<Eigen::Vector2d> marbles = rolling.positions();
    cv::Mat frame;
    if (rendering.interlace) {
      rolling.step(0.5 / a.fps);  // the odd rows' instant
      frame = renderer.render(marbles, camera, rolling.positions(), odd_camera, world.marble_diameter, f);
      rolling.step(0.5 / a.fps);
    } else {
      frame = renderer.render(marbles, world.marble_diameter, camera, f);
      rolling.step(1 / a.fps);
    }
    if (compression.codec == "jpeg") frame = sim::jpeg_loss(frame, compression.quality);
    cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
    writer->write(bgr);
    if (truth.is_open()) {
      write_truth_rows(truth, sim::marble_truth(marbles, world.marble_diameter, camera, rendering.shape), f);
    }
    bar.update(f + 1);
  }
  bar.clear();
  std::cerr << fmt::format("neopipe sim video: {} camera, {} realism, {} frames of {}x{} (codec {}{}) -> {}\n",
                           a.cam.camera, a.cam.realism, frames, fixed.size().width, fixed.size().height,
                           compression.codec,
                           compression.codec == "jpeg" ? fmt::format(" {}", compression.quality) : "", a.cam.out);
  return kExitOk;
}

}  // namespace neopipe::apps
