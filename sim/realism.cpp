#include "sim/realism.hpp"

#include <stdexcept>

namespace neopipe::sim {

Realism parse_realism(std::string_view text) {
  if (text == "ideal") return Realism::ideal;
  if (text == "rig") return Realism::rig;
  if (text == "harsh") return Realism::harsh;
  throw std::invalid_argument("realism '" + std::string(text) + "': unknown (ideal, rig or harsh)");
}

std::string realism_name(Realism r) {
  switch (r) {
    case Realism::ideal:
      return "ideal";
    case Realism::rig:
      return "rig";
    case Realism::harsh:
      return "harsh";
  }
  return "?";
}

namespace {

// The global camera's lens under each preset: GlobalCameraConfig's OpenCV terms, and beyond them a
// radial r^8 term and thin prism sized so that a five-term OpenCV fit over the whole image leaves
// about 0.03 px RMS (rig) or four times that (harsh); tests/sim/test_lens.cpp measures it. Most of
// these terms a five-term fit absorbs (r^8 into k1..k3, the prism into the decentring terms and
// the principal point): what it cannot is the residual.
Lens global_lens(Realism r) {
  Lens lens;
  lens.opencv = GlobalCameraConfig{}.distortion;
  if (r == Realism::rig) lens.extra = {5, 5.0e-4, -4.0e-3, -4.0e-4, 3.5e-3};
  if (r == Realism::harsh) {
    lens.opencv = {-0.10, 0.03, 0.001, -0.0008, 0};
    lens.extra = {25, 4.0e-3, -2.0e-2, -3.0e-3, 2.0e-2};
  }
  return lens;
}

// The onboard camera's lens: none under ideal (today's); under rig mild barrel and prism, at most
// about 0.3 px at the corners, that the navigator's model of its camera does not know about.
Lens onboard_lens(Realism r) {
  Lens lens;
  if (r == Realism::rig) {
    lens.opencv = {-0.012, 0, 0, 0, 0};
    lens.extra = {0, 1.0e-4, 0, -1.0e-4, 0};
  }
  if (r == Realism::harsh) {
    lens.opencv = {-0.04, 0.01, 0.0005, -0.0004, 0};
    lens.extra = {0, 5.0e-4, 0, -5.0e-4, 0};
  }
  return lens;
}

}  // namespace

Rendering rendering_for(Realism realism, CameraKind camera, const Eigen::Vector2d& workspace) {
  const bool global = camera == CameraKind::global;
  Rendering r;  // ImageModel's defaults: the ideal preset
  r.lens = global ? global_lens(realism) : onboard_lens(realism);
  if (realism == Realism::ideal) return r;

  const bool harsh = realism == Realism::harsh;
  r.shape = MarbleShape::sphere;
  PointLight light;
  light.position = {0, workspace.y(), harsh ? 700.0 : 1500.0};  // above the north-west corner
  light.ambient = harsh ? 0.4 : 0.45;
  light.specular = harsh ? 90 : 35;
  light.shininess = harsh ? 40 : 60;
  r.light = light;
  r.surfaces.texture = harsh ? 0.10 : 0.05;
  r.defocus = global ? Defocus{harsh ? 0.9 : 0.7, harsh ? 2.0 : 1.1} : Defocus{harsh ? 1.0 : 0.8, harsh ? 2.2 : 1.3};
  r.sensor.read_noise = harsh ? 3 : 1.5;
  r.sensor.full_well = harsh ? 4000 : 12000;
  r.sensor.prnu = harsh ? 0.02 : 0.01;
  r.sensor.vignetting = harsh ? 0.25 : (global ? 0.12 : 0.08);
  r.sensor.gradient = 0;  // the point light makes the real gradient
  r.interlace = harsh;
  r.validate();
  return r;
}

OnboardCameraConfig onboard_config_for(const Rendering& rendering, double marble_diameter, OnboardCameraConfig base) {
  base.window_plane_z = rendering.shape == MarbleShape::sphere ? marble_diameter / 2 : 0.0;
  return base;
}

}  // namespace neopipe::sim
