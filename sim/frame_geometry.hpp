#pragma once
// One frame's scene in its camera's frame (camera at the origin looking along +z): the table
// plane, the light. Rays come from the RayTable as (x, y, 1), so a pixel's ray meets the scene
// without the world-to-camera rotation per pixel.

#include <Eigen/Core>
#include <optional>

#include "sim/camera.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

struct FrameGeometry {
  FrameGeometry(const PinholeCamera& camera, const std::optional<PointLight>& light);

  Eigen::Matrix3d rotation;              ///< world to camera: Xc = R Xw + t
  Eigen::Vector3d translation;           ///< t
  Eigen::Vector3d up;                    ///< the world's +z in the camera's frame: the table's normal
  double table_level = 0;                ///< up . X for points X of the table (z = 0), camera frame
  std::optional<Eigen::Vector3d> light;  ///< the light's position, camera frame
  double light_height = 0;               ///< mm above the table

  [[nodiscard]] Eigen::Vector3d to_camera(const Eigen::Vector3d& world) const { return rotation * world + translation; }
  [[nodiscard]] Eigen::Vector3d to_world(const Eigen::Vector3d& camera) const {
    return rotation.transpose() * (camera - translation);
  }
  /// Where the ray (x, y, 1) meets the table, or nothing if it does not (in front of the camera).
  [[nodiscard]] std::optional<Eigen::Vector3d> table_point(const Eigen::Vector2d& ray) const {
    const Eigen::Vector3d d(ray.x(), ray.y(), 1);
    const double along = up.dot(d);
    if (along >= -1e-12) return std::nullopt;  // parallel to the table or going up, away from it
    const double s = table_level / along;
    if (s <= 0) return std::nullopt;
    return Eigen::Vector3d(s * d);
  }
};

}  // namespace neopipe::sim
