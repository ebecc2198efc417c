#include "sim/frame_geometry.hpp"

namespace neopipe::sim {

FrameGeometry::FrameGeometry(const PinholeCamera& camera, const std::optional<PointLight>& l)
    : rotation(camera.rotation()), translation(camera.translation()), up(camera.rotation().col(2)) {
  table_level = up.dot(translation);
  if (l) {
    light = to_camera(l->position);
    light_height = l->position.z();
  }
}

}  // namespace neopipe::sim
