#include "sim/rendering.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string_view>

namespace neopipe::sim {
namespace {

void require(bool ok, std::string_view field, std::string_view rule, double got) {
  if (!ok) throw std::invalid_argument(fmt::format("{}: must be {} (got {})", field, rule, got));
}

// Finite and within [lo, hi].
void in_range(double v, double lo, double hi, std::string_view field, std::string_view unit = "") {
  require(std::isfinite(v) && v >= lo && v <= hi, field, fmt::format("{} .. {}{}", lo, hi, unit), v);
}

}  // namespace

void Rendering::validate() const {
  const Surfaces& s = surfaces;
  in_range(s.table, 0, 255, "surfaces.table", " gray levels");
  in_range(s.marble, 0, 1e4, "surfaces.marble", " gray levels");
  in_range(s.disk_rim, 0, 1, "surfaces.disk_rim");
  require(std::isfinite(s.texture) && s.texture >= 0 && s.texture < 1, "surfaces.texture", "in [0, 1)", s.texture);
  require(std::isfinite(s.texture_scale) && s.texture_scale > 0, "surfaces.texture_scale", "> 0 mm", s.texture_scale);
  if (light) {
    const Eigen::Vector3d& p = light->position;
    if (!p.allFinite()) throw std::invalid_argument("light.position: must be three finite numbers (mm)");
    if (!(p.z() > 0)) {
      throw std::invalid_argument(
          fmt::format("light.position: z = {} mm is at or below the table; the light must be above it", p.z()));
    }
    in_range(light->ambient, 0, 1, "light.ambient");
    in_range(light->specular, 0, 1e4, "light.specular", " gray levels");
    in_range(light->shininess, 1, 1e4, "light.shininess");
  }
  for (std::size_t i = 0; i < lens.opencv.size(); ++i) {
    static constexpr std::string_view kNames[] = {"k1", "k2", "p1", "p2", "k3"};
    require(std::isfinite(lens.opencv[i]), fmt::format("lens.{}", kNames[i]), "finite", lens.opencv[i]);
  }
  const auto extra = lens.extra.as_array();
  for (std::size_t i = 0; i < extra.size(); ++i) {
    static constexpr std::string_view kNames[] = {"k4", "s1", "s2", "s3", "s4"};
    require(std::isfinite(extra[i]), fmt::format("lens.{}", kNames[i]), "finite", extra[i]);
  }
  if (const auto fold = lens_fold_radius(lens, kLensCheckField)) {
    throw std::invalid_argument(fmt::format(
        "lens: the distortion folds the image at normalised radius {:.3f} (checked to {}): it must be one-to-one",
        *fold, kLensCheckField));
  }
  in_range(defocus.centre, 0, 8, "defocus.centre", " px");
  in_range(defocus.corner, 0, 8, "defocus.corner", " px");
  in_range(sensor.read_noise, 0, 64, "sensor.read_noise", " gray levels");
  if (sensor.full_well) {
    require(std::isfinite(*sensor.full_well) && *sensor.full_well > 0, "sensor.full_well", "> 0 electrons",
            *sensor.full_well);
  }
  require(std::isfinite(sensor.prnu) && sensor.prnu >= 0 && sensor.prnu < 0.5, "sensor.prnu", "in [0, 0.5)",
          sensor.prnu);
  require(std::isfinite(sensor.vignetting) && sensor.vignetting >= 0 && sensor.vignetting < 1, "sensor.vignetting",
          "in [0, 1)", sensor.vignetting);
  in_range(sensor.gradient, 0, 0.9, "sensor.gradient");
  require(std::isfinite(sensor.gradient_angle_deg), "sensor.gradient_angle_deg", "finite", sensor.gradient_angle_deg);
}

bool Rendering::is_image_model() const {
  return shape == MarbleShape::disk && !light && surfaces.texture == 0 && !lens.extra.any() &&
         defocus.corner == defocus.centre && !sensor.full_well && sensor.prnu == 0 && sensor.vignetting == 0 &&
         !interlace;
}

ImageModel Rendering::image_model() const {
  ImageModel m;
  m.background = surfaces.table;
  m.marble = surfaces.marble;
  m.rim = surfaces.disk_rim;
  m.gradient = sensor.gradient;
  m.gradient_angle_deg = sensor.gradient_angle_deg;
  m.blur_sigma = defocus.centre;
  m.noise_sigma = sensor.read_noise;
  m.seed = sensor.seed;
  return m;
}

Rendering rendering_from(const ImageModel& model, const Lens& lens) {
  Rendering r;
  r.surfaces.table = model.background;
  r.surfaces.marble = model.marble;
  r.surfaces.disk_rim = model.rim;
  r.sensor.gradient = model.gradient;
  r.sensor.gradient_angle_deg = model.gradient_angle_deg;
  r.defocus = {model.blur_sigma, model.blur_sigma};
  r.sensor.read_noise = model.noise_sigma;
  r.sensor.seed = model.seed;
  r.lens = lens;
  return r;
}

}  // namespace neopipe::sim
