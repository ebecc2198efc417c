#include "python/src/reports.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <cstring>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "calib/calibration.hpp"
#include "calib/estimate.hpp"
#include "calib/image_calibration.hpp"
#include "calib/plane_pose.hpp"
#include "calib/points_csv.hpp"
#include "rig/reports.hpp"
#include "sim/cameras.hpp"
#include "sim/marble_truth.hpp"
#include "sim/realism.hpp"
#include "sim/scene_renderer.hpp"
#include "sim/world.hpp"

namespace neopipe::python {
namespace {

namespace py = pybind11;

// The CLI prints nlohmann::json; Python gets the same text parsed by its own json module, so the
// dictionaries are equal to `json.loads` of the CLI's output, key for key and number for number.
py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<Eigen::Vector2d> points_of(const Points& a, const char* what, const char* columns) {
  const bool one = a.ndim() == 1 && a.shape(0) == 2;
  if (!one && !(a.ndim() == 2 && a.shape(1) == 2)) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
    throw py::value_error(fmt::format("{}: shape ({}); expected N x 2 ({})", what, shape, columns));
  }
  const py::ssize_t n = one ? 1 : a.shape(0);
  std::vector<Eigen::Vector2d> out(static_cast<std::size_t>(n));
  const double* p = a.data();
  for (py::ssize_t i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = {p[2 * i], p[2 * i + 1]};
  return out;
}

py::array points_array(const std::vector<Eigen::Vector2d>& points, bool one) {
  py::array_t<double> out(one ? std::vector<py::ssize_t>{2}
                              : std::vector<py::ssize_t>{static_cast<py::ssize_t>(points.size()), 2});
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < points.size(); ++i) {
    p[2 * i] = points[i].x();
    p[2 * i + 1] = points[i].y();
  }
  return out;
}

py::array mat_array(const cv::Mat& m) {
  if (m.empty()) return py::array_t<double>(std::vector<py::ssize_t>{0});
  cv::Mat d;
  m.convertTo(d, CV_64F);
  py::array_t<double> out({static_cast<py::ssize_t>(d.rows), static_cast<py::ssize_t>(d.cols)});
  for (int y = 0; y < d.rows; ++y) std::memcpy(out.mutable_data(y, 0), d.ptr<double>(y), sizeof(double) * d.cols);
  return out;
}

py::dict stats_dict(const calib::ErrorStats& s) {
  py::dict d;
  d["mean"] = py::make_tuple(s.mean.x(), s.mean.y());
  d["sd"] = py::make_tuple(s.sd.x(), s.sd.y());
  d["rms"] = s.rms;
  d["max"] = s.max;
  d["points"] = s.points;
  return d;
}

struct Calibration {
  calib::Calibration c;

  py::array image_to_world(const Points& uv, double height) const {
    const auto pixels = points_of(uv, "uv", "u, v pixel coordinates");
    std::vector<Eigen::Vector2d> world;
    {
      py::gil_scoped_release release;
      world = calib::to_world_at_height(c, pixels, height);
    }
    return points_array(world, uv.ndim() == 1);
  }
  py::array world_to_image(const Points& xy, double height) const {
    const auto world = points_of(xy, "xy", "X, Y workspace mm");
    std::vector<Eigen::Vector2d> pixels;
    {
      py::gil_scoped_release release;
      pixels = calib::to_pixel_at_height(c, world, height);
    }
    return points_array(pixels, xy.ndim() == 1);
  }
  py::dict report() const {
    const auto& r = c.report;
    py::dict d;
    d["fit"] = stats_dict(r.fit);
    d["held_out"] = stats_dict(r.held_out);
    d["reprojection_rms_px"] = r.reprojection_rms_px;
    d["homography_held_out_rms"] =
        r.homography_held_out_rms >= 0 ? py::object(py::float_(r.homography_held_out_rms)) : py::object(py::none());
    d["full_held_out_rms"] =
        r.full_held_out_rms >= 0 ? py::object(py::float_(r.full_held_out_rms)) : py::object(py::none());
    d["views_used"] = r.views_used;
    d["views_rejected"] = r.views_rejected;
    d["points_used"] = r.points_used;
    d["points_rejected"] = r.points_rejected;
    d["rejected"] = r.rejected;
    return d;
  }
};

std::optional<cv::Size> size_of(const std::optional<std::pair<int, int>>& s, const char* what) {
  if (!s) return std::nullopt;
  if (s->first <= 0 || s->second <= 0) {
    throw py::value_error(fmt::format("{} ({}, {}): must be positive (width, height)", what, s->first, s->second));
  }
  return cv::Size(s->first, s->second);
}

Calibration calibrate(const std::vector<std::string>& images, const std::string& target,
                      const std::optional<std::string>& points, const std::vector<double>& origin,
                      const std::string& model, double inlier_mm,
                      const std::optional<std::pair<int, int>>& image_size) {
  if (model != "auto" && model != "homography" && model != "full") {
    throw py::value_error("model '" + model + "': must be auto, homography or full");
  }
  if (!(inlier_mm > 0)) throw py::value_error(fmt::format("inlier_mm {}: must be > 0", inlier_mm));
  if (points.has_value() == !target.empty()) throw py::value_error("give either target with images, or points");
  Calibration out;
  if (points) {
    if (!images.empty()) throw py::value_error("points takes no images");
    if (model == "full") throw py::value_error("points give one plane's pairs: only the homography model fits them");
    const calib::Correspondences pairs = calib::read_points_csv(*points);
    calib::EstimateOptions o;
    o.ransac.inlier_mm = inlier_mm;
    const cv::Size size = size_of(image_size, "image_size").value_or(cv::Size(0, 0));
    py::gil_scoped_release release;
    out.c = calib::calibrate_homography(pairs, size, o);
    return out;
  }
  if (images.empty()) throw py::value_error("target needs images of the target");
  if (origin.size() != 2 && origin.size() != 3) {
    throw py::value_error("target_origin: expected (X, Y) or (X, Y, THETA) (mm, mm, degrees)");
  }
  calib::ImageCalibrationOptions o;
  o.target = calib::parse_target(target);
  o.origin = {origin[0], origin[1], origin.size() == 3 ? origin[2] : 0.0};
  o.model = model;
  o.inlier_mm = inlier_mm;
  py::gil_scoped_release release;
  out.c = calib::calibrate_images(images, o).calibration;
  return out;
}

// --------------------------------------------------------------------------------------------------------------
// The simulator

struct World {
  sim::World w;
  py::array objects() const { return points_array(w.objects, false); }
};

py::tuple render(const World& world, const std::string& camera, const std::string& realism,
                 const std::optional<std::vector<double>>& pose, std::uint64_t seed,
                 const std::pair<int, int>& resolution, double window) {
  if (camera != "global" && camera != "onboard") {
    throw py::value_error("camera '" + camera + "': must be global or onboard");
  }
  const bool global = camera == "global";
  if (global && pose) throw py::value_error("pose is for the onboard camera; the global camera stays put");
  const sim::World& w = world.w;
  sim::Rendering r = sim::rendering_for(sim::parse_realism(realism),
                                        global ? sim::CameraKind::global : sim::CameraKind::onboard, w.size);
  r.sensor.seed = seed;
  cv::Mat frame;
  std::vector<sim::MarbleTruth> truth;
  {
    py::gil_scoped_release release;
    std::optional<sim::PinholeCamera> cam;
    if (global) {
      sim::GlobalCameraConfig c;
      c.resolution = *size_of(resolution, "resolution");
      cam = sim::make_global_camera(w.size, c, r);
    } else {
      sim::Pose2 p{w.size.x() / 2, w.size.y() / 2, 0};
      if (pose) {
        if (pose->size() != 3) throw py::value_error("pose: expected (x, y, theta) (mm, mm, degrees)");
        // Degrees, as the CLI's --pose takes them; the simulator's poses are in radians.
        p = {(*pose)[0], (*pose)[1], (*pose)[2] * std::numbers::pi / 180};
        if (!(p.x >= 0 && p.y >= 0 && p.x <= w.size.x() && p.y <= w.size.y())) {
          throw py::value_error(
              fmt::format("pose ({}, {}) is outside the {} x {} mm workspace", p.x, p.y, w.size.x(), w.size.y()));
        }
      }
      sim::OnboardCameraConfig c;
      c.window_mm = window;
      cam = sim::make_onboard_camera(p, sim::onboard_config_for(r, w.marble_diameter, c), r);
    }
    const sim::SceneRenderer renderer(r, *cam);
    frame = renderer.render(w.objects, w.marble_diameter, *cam, 0);
    truth = sim::marble_truth(w.objects, w.marble_diameter, *cam, r.shape);
  }
  py::array image(py::dtype::of<std::uint8_t>(), std::vector<py::ssize_t>{frame.rows, frame.cols});
  for (int y = 0; y < frame.rows; ++y) {
    std::memcpy(static_cast<std::uint8_t*>(image.mutable_data()) + static_cast<std::size_t>(y) * frame.cols,
                frame.ptr(y), static_cast<std::size_t>(frame.cols));
  }
  py::list rows;
  for (const auto& t : truth) rows.append(py::make_tuple(t.id, t.u, t.v, t.u0, t.v0));
  return py::make_tuple(image, rows);
}

}  // namespace

void bind_reports(py::module_& m) {
  py::class_<Calibration>(m, "Calibration")
      .def_static(
          "load", [](const std::string& path) { return Calibration{calib::load_calibration(path)}; }, py::arg("path"))
      .def(
          "save", [](const Calibration& c, const std::string& path) { calib::save_calibration(c.c, path); },
          py::arg("path"))
      .def("image_to_world", &Calibration::image_to_world, py::arg("uv"), py::arg("height") = 0.0)
      .def("world_to_image", &Calibration::world_to_image, py::arg("xy"), py::arg("height") = 0.0)
      .def_property_readonly("model", [](const Calibration& c) { return calib::model_name(c.c.model); })
      .def_property_readonly("image_size",
                             [](const Calibration& c) -> py::object {
                               if (c.c.image_size.area() <= 0) return py::none();
                               return py::make_tuple(c.c.image_size.width, c.c.image_size.height);
                             })
      .def_property_readonly("camera_matrix", [](const Calibration& c) { return mat_array(c.c.camera_matrix); })
      .def_property_readonly("distortion_coefficients",
                             [](const Calibration& c) { return mat_array(c.c.distortion_coefficients); })
      .def_property_readonly("homography",
                             [](const Calibration& c) {
                               py::array_t<double> h({3, 3});
                               for (int i = 0; i < 3; ++i)
                                 for (int k = 0; k < 3; ++k) h.mutable_at(i, k) = c.c.image_to_world(i, k);
                               return h;
                             })
      .def_property_readonly("report", &Calibration::report);
  m.def("calibrate", &calibrate, py::arg("images"), py::arg("target"), py::arg("points"), py::arg("origin"),
        py::arg("model"), py::arg("inlier_mm"), py::arg("image_size"));

  py::class_<World>(m, "World")
      .def_static(
          "load", [](const std::string& path) { return World{sim::load_world(path)}; }, py::arg("path"))
      .def_static(
          "generate",
          [](int objects, std::pair<double, double> size, double diameter, double min_gap, std::uint64_t seed) {
            if (objects < 0) throw py::value_error(fmt::format("objects {}: must be >= 0", objects));
            if (!(size.first > 0 && size.second > 0)) throw py::value_error("size: width and height must be > 0 mm");
            if (!(diameter > 0)) throw py::value_error(fmt::format("diameter {}: must be > 0 mm", diameter));
            if (!(min_gap >= 0)) throw py::value_error(fmt::format("min_gap {}: must be >= 0 mm", min_gap));
            sim::WorldRequest q;
            q.objects = objects;
            q.size = {size.first, size.second};
            q.marble_diameter = diameter;
            q.min_gap = min_gap;
            q.seed = seed;
            py::gil_scoped_release release;
            return World{sim::generate_world(q)};
          },
          py::arg("objects"), py::arg("size"), py::arg("diameter"), py::arg("min_gap"), py::arg("seed"))
      .def(
          "save", [](const World& w, const std::string& path) { sim::save_world(w.w, path); }, py::arg("path"))
      .def_property_readonly("size", [](const World& w) { return py::make_tuple(w.w.size.x(), w.w.size.y()); })
      .def_property_readonly("marble_diameter", [](const World& w) { return w.w.marble_diameter; })
      .def_property_readonly("objects", &World::objects);
  m.def("render", &render, py::arg("world"), py::arg("camera"), py::arg("realism"), py::arg("pose"), py::arg("seed"),
        py::arg("resolution"), py::arg("window"));

  m.def(
      "map_report",
      [](const std::string& world, const std::string& blobs, const std::optional<std::pair<double, double>>& size,
         double window, std::optional<double> margin, std::optional<double> sigma, double border_tolerance,
         const std::string& descriptions, const std::string& calib, double move_error, double rotation_error,
         std::optional<std::int64_t> from, std::optional<std::int64_t> to, const std::string& cost,
         double reliable_threshold) {
        rig::MapRequest r;
        r.world = world;
        r.blobs = blobs;
        if (size) r.size = Eigen::Vector2d(size->first, size->second);
        r.window = window;
        r.margin = margin;
        r.sigma = sigma;
        r.border_tolerance = border_tolerance;
        r.descriptions = descriptions;
        r.calib = calib;
        r.move_error = move_error;
        r.rotation_error = rotation_error;
        r.from = from;
        r.to = to;
        r.cost = cost;
        r.reliable_threshold = reliable_threshold;
        nlohmann::json j;
        {
          py::gil_scoped_release release;
          j = rig::map_report(r).json;
        }
        return to_python(j);
      },
      py::arg("world"), py::arg("blobs"), py::arg("size"), py::arg("window"), py::arg("margin"), py::arg("sigma"),
      py::arg("border_tolerance"), py::arg("descriptions"), py::arg("calib"), py::arg("move_error"),
      py::arg("rotation_error"), py::arg("start"), py::arg("goal"), py::arg("cost"), py::arg("reliable_threshold"));

  m.def(
      "nav_trials",
      [](const std::string& world, std::int64_t trials, const std::string& cost, std::optional<double> sigma_map,
         const std::string& realism, const std::string& cache_dir, bool no_cache, double sigma_move, double sigma_rot,
         std::uint64_t seed, bool recovery, const std::string& navigator, const std::string& descriptions,
         double min_reliability, double window, int threads) {
        rig::NavRequest r;
        r.world = world;
        r.cost = cost;
        r.sigma_map = sigma_map;
        r.realism = realism;
        r.cache_dir = cache_dir;
        r.no_cache = no_cache;
        r.sigma_move = sigma_move;
        r.sigma_rot = sigma_rot;
        r.seed = seed;
        r.no_recovery = !recovery;
        r.navigator = navigator;
        r.descriptions = descriptions;
        r.min_reliability = min_reliability;
        r.window = window;
        r.threads = threads;
        // As the CLI: the survey's progress lines (a calibration session can take a while) on stderr.
        r.note = [](const std::string& line) { std::cerr << "neopipe.nav: " << line << '\n'; };
        nlohmann::json j;
        {
          py::gil_scoped_release release;
          const rig::NavSetup setup = rig::nav_setup(r);
          j = rig::trials_report(r, setup, trials).json;
        }
        return to_python(j);
      },
      py::arg("world"), py::arg("trials"), py::arg("cost"), py::arg("sigma_map"), py::arg("realism"),
      py::arg("cache_dir"), py::arg("no_cache"), py::arg("sigma_move"), py::arg("sigma_rot"), py::arg("seed"),
      py::arg("recovery"), py::arg("navigator"), py::arg("descriptions"), py::arg("min_reliability"), py::arg("window"),
      py::arg("threads"));
}

}  // namespace neopipe::python
