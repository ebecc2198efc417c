#pragma once
// How one camera of the rig turns the scene into pixels: the marbles' shape, the light, the table,
// the lens, vignetting, defocus and the sensor. Every effect can be switched off on its own; with
// all of them off (flat disks, no light, OpenCV's lens, a uniform blur, Gaussian noise) it is
// today's ImageModel, and SceneRenderer renders exactly today's images. Presets: sim/realism.hpp.
//
// Gray levels: a surface's albedo is the gray level it would have facing the light straight below
// it, at the light's height, at the image centre, before the sensor's noise.

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "sim/image_model.hpp"
#include "sim/lens.hpp"

namespace neopipe::sim {

enum class MarbleShape {
  disk,   ///< a flat disk in the table plane, shaded as a dome (today's model)
  sphere  ///< a ball of the world's diameter resting on the table: its centre at height d / 2
};

/// A point light above the table, Lambertian shading plus ambient, a Blinn-Phong highlight on the
/// marbles (the table and calibration boards are matte), and the marbles' shadows on the table.
struct PointLight {
  Eigen::Vector3d position{0, 500, 1500};  ///< mm, world; must be above the marbles
  double ambient = 0.45;                   ///< fraction of full light that every surface gets whatever its direction
  double specular = 35;                    ///< gray levels at the centre of a marble's highlight (0: none)
  double shininess = 60;                   ///< Blinn-Phong exponent: larger, smaller highlights
  bool shadows = true;                     ///< marbles shadow the table (and each other)
};

struct Surfaces {
  double table = 40;    ///< table albedo, gray levels
  double marble = 210;  ///< marble albedo, gray levels; a disk's centre under ImageModel
  /// Disks only: brightness at the rim as a fraction of the centre's excess (ImageModel::rim).
  double disk_rim = 0.45;
  double texture = 0;              ///< table texture amplitude: albedo x (1 + texture x noise in [-1, 1])
  double texture_scale = 6;        ///< mm, the coarser of the texture's two octaves (the finer is half)
  std::uint64_t texture_seed = 1;  ///< the table's pattern: a property of the world, not of the noise
};

/// Blur: Gaussian, sigma growing with the square of the distance from the image centre, from
/// `centre` to `corner` at the image corners (a lens focused at the centre of a flat field).
struct Defocus {
  double centre = 0.7;  ///< px
  double corner = 0.7;  ///< px
};

struct Sensor {
  double read_noise = 2;  ///< gray levels, sigma of additive Gaussian noise (ImageModel::noise_sigma)
  /// Electrons at full scale (gray 255): photon shot noise has variance gray x 255 / full_well in
  /// gray levels squared. Nothing: no shot noise.
  std::optional<double> full_well;
  double prnu = 0;  ///< sigma of each pixel's gain about 1, fixed per camera (seed)
  /// Fraction of light lost at the image corners (gain 1 - vignetting x (radius / half diagonal)^2).
  double vignetting = 0;
  double gradient = 0.15;          ///< ImageModel::gradient: +- this fraction across the image
  double gradient_angle_deg = 30;  ///< ImageModel::gradient_angle_deg
  std::uint64_t seed = 1;          ///< noise and PRNU; a frame's noise also depends on its index
};

struct Rendering {
  MarbleShape shape = MarbleShape::disk;
  std::optional<PointLight> light;  ///< nothing: uniform light, no shading, highlight or shadow
  Surfaces surfaces{};
  Lens lens{};  ///< what make_global_camera / make_onboard_camera (sim/cameras.hpp) give the camera
  Defocus defocus{};
  Sensor sensor{};
  bool interlace = false;  ///< even rows taken at the frame's instant, odd rows half a frame later

  /// Throws std::invalid_argument with a one-line message naming the first bad field, e.g.
  /// "sensor.full_well: must be > 0 electrons (got 0)".
  void validate() const;
  /// Whether this is exactly today's ImageModel (disks, no light, texture, extra lens terms,
  /// vignetting, defocus growth, shot noise, PRNU or interlace).
  [[nodiscard]] bool is_image_model() const;
  /// Today's ImageModel with these settings' shared fields.
  [[nodiscard]] ImageModel image_model() const;
};

/// Settings that render what `model` renders (MarbleRenderer), with `lens` for the camera.
Rendering rendering_from(const ImageModel& model, const Lens& lens = {});

/// The largest normalised image radius (tan of the angle off the optical axis) the lens is checked
/// over by Rendering::validate: beyond the corners of both rig cameras (about 0.46 and 0.36). The
/// camera makers check a camera's own corners.
inline constexpr double kLensCheckField = 0.6;

}  // namespace neopipe::sim
