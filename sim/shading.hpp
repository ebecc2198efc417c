#pragma once
// How a surface point is lit by the PointLight: Lambertian irradiance with the inverse-square
// fall-off, ambient, and a Blinn-Phong highlight. Points, normals and the light in the camera's
// frame (the viewer at the origin).

#include <Eigen/Core>
#include <cmath>

#include "sim/rendering.hpp"

namespace neopipe::sim {

class Shader {
 public:
  /// `light_position` in the camera's frame, `light_height` mm above the table.
  // NOLINTNEXTLINE(modernize-pass-by-value): the members after light_ read `light`
  Shader(const PointLight& light, const Eigen::Vector3d& light_position, double light_height)
      : light_(light),
        position_(light_position),
        height2_(light_height * light_height),
        // Below this cosine the highlight is under a thousandth of its peak: no pow needed.
        cutoff_(std::pow(1e-3, 1 / light.shininess)),
        // Beyond this angle from the mirror direction the highlight is under half a gray level.
        visible_angle_(light.specular > 0.5 ? std::acos(std::pow(0.5 / light.specular, 1 / light.shininess)) : 0.0),
        whole_(light.shininess == std::floor(light.shininess) && light.shininess <= 256
                   ? static_cast<unsigned>(light.shininess)
                   : 0U) {}

  /// Direct irradiance, a fraction of full light (a surface facing the light straight below it, at
  /// the light's height): cos(normal, towards the light) x (height / distance)^2; 0 facing away.
  [[nodiscard]] double direct(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const {
    const Eigen::Vector3d to_light = position_ - point;
    const double d2 = to_light.squaredNorm();
    const double cosine = normal.dot(to_light) / std::sqrt(d2);
    return cosine > 0 ? cosine * height2_ / d2 : 0.0;
  }
  /// The table's, at a point of it: (height / distance)^3.
  [[nodiscard]] double table_direct(const Eigen::Vector3d& point) const {
    const double q2 = height2_ / (position_ - point).squaredNorm();
    return q2 * std::sqrt(q2);
  }
  /// The share of full light a surface gets: ambient, plus the rest times the direct irradiance.
  [[nodiscard]] double lit(double direct) const { return light_.ambient + (1 - light_.ambient) * direct; }
  /// The Blinn-Phong highlight (gray levels) at `point` with unit `normal`.
  [[nodiscard]] double highlight(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const {
    if (light_.specular <= 0) return 0;
    const Eigen::Vector3d to_light = position_ - point;
    const double d2 = to_light.squaredNorm();
    const Eigen::Vector3d l = to_light / std::sqrt(d2);
    if (normal.dot(l) <= 0) return 0;
    const double c = normal.dot((l - point.normalized()).normalized());
    if (c <= cutoff_) return 0;
    return light_.specular * std::pow(c, light_.shininess) * height2_ / d2;
  }
  /// The light leaving a surface of `albedo` (gray levels) at `point` with unit `normal` towards
  /// the viewer: albedo x lit(direct) + highlight, in one pass over the shared vectors. If
  /// `mirror` is given, the cosine of the normal's angle from the mirror direction goes there
  /// (-1 facing away from the light).
  [[nodiscard]] double surface(double albedo, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                               double* mirror = nullptr) const {
    const Eigen::Vector3d to_light = position_ - point;
    const double d2 = to_light.squaredNorm();
    const double inverse = 1 / std::sqrt(d2);
    const double cosine = normal.dot(to_light) * inverse;
    if (mirror) *mirror = -1;
    if (cosine <= 0) return albedo * light_.ambient;
    const double falloff = height2_ / d2;
    double out = albedo * lit(cosine * falloff);
    if (light_.specular > 0) {
      const Eigen::Vector3d half = (to_light * inverse - point.normalized()).normalized();
      const double c = normal.dot(half);
      if (mirror) *mirror = c;
      if (c > cutoff_) out += light_.specular * power(c) * falloff;
    }
    return out;
  }
  /// The angle (radians) from the mirror direction beyond which the highlight is under half a gray
  /// level (0: no highlight).
  [[nodiscard]] double visible_angle() const { return visible_angle_; }
  [[nodiscard]] const Eigen::Vector3d& position() const { return position_; }
  [[nodiscard]] const PointLight& light() const { return light_; }

 private:
  // c^shininess: by squaring for whole exponents up to 256 (a few multiplications instead of pow).
  [[nodiscard]] double power(double c) const {
    if (whole_ == 0) return std::pow(c, light_.shininess);
    double result = 1;
    for (unsigned e = whole_; e != 0; e >>= 1U, c *= c) {
      if ((e & 1U) != 0) result *= c;
    }
    return result;
  }

  PointLight light_;
  Eigen::Vector3d position_;
  double height2_;
  double cutoff_;
  double visible_angle_;
  unsigned whole_;  // the exponent if it is a whole number up to 256, else 0
};

}  // namespace neopipe::sim
