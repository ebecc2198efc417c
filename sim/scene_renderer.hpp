#pragma once
// Renders the world's marbles as one camera of the rig sees them under a Rendering
// (sim/rendering.hpp; presets in sim/realism.hpp): spheres or flat disks, the point light with
// shading, highlights and shadows, the textured table, the lens, defocus, vignetting and the
// sensor's noise. Settings that are exactly today's ImageModel go through MarbleRenderer, so
// `ideal` frames are today's bit for bit.
//
// How a frame is made: the bare table's light (TableField), then for each group of marbles whose
// patches overlap, their patch (sim/marble_patch.hpp: rays cast per pixel, outlines and shadow
// edges area-sampled) blurred with the defocus at its place (DefocusBlur) and added, then the
// sensor (SensorModel). The camera's rays are computed once per renderer: its intrinsics and lens
// are fixed, only its pose changes. The table's light is cached for the pose the renderer was made
// with (the global camera never moves).

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <span>

#include "sim/camera.hpp"
#include "sim/defocus.hpp"
#include "sim/marble_renderer.hpp"
#include "sim/ray_table.hpp"
#include "sim/rendering.hpp"
#include "sim/sensor_model.hpp"
#include "sim/table_field.hpp"
#include "sim/table_texture.hpp"

namespace neopipe::sim {

class SceneRenderer {
 public:
  /// For frames of cameras with `camera`'s intrinsics and lens (any pose; `camera`'s own pose gets
  /// the cached table). Validates `rendering` (std::invalid_argument naming the field).
  SceneRenderer(const Rendering& rendering, const PinholeCamera& camera);

  /// One 8-bit frame of marbles of `diameter` centred at `centres` (mm, world x, y), seen by
  /// `camera` (this renderer's intrinsics). `frame` selects the noise. Interlaced settings take both
  /// fields from this one scene (nothing moved within the frame).
  [[nodiscard]] cv::Mat render(std::span<const Eigen::Vector2d> centres, double diameter, const PinholeCamera& camera,
                               std::int64_t frame) const;
  /// An interlaced frame: even rows see `even_centres` through `even_camera`, odd rows (taken half
  /// a frame later) `odd_centres` through `odd_camera`. Without interlace: the even field alone.
  [[nodiscard]] cv::Mat render(std::span<const Eigen::Vector2d> even_centres, const PinholeCamera& even_camera,
                               std::span<const Eigen::Vector2d> odd_centres, const PinholeCamera& odd_camera,
                               double diameter, std::int64_t frame) const;

  /// The light reaching the sensor (CV_32F gray levels, before vignetting, PRNU and noise), by the
  /// ray-cast path whatever the settings (disks too): what render() quantises, for tests.
  [[nodiscard]] cv::Mat radiance(std::span<const Eigen::Vector2d> centres, double diameter,
                                 const PinholeCamera& camera) const;
  /// Any scene's light (CV_32F gray levels, this renderer's size) through the defocus (the whole
  /// frame, sigma by position), vignetting, PRNU, noise and quantisation: how calibration targets
  /// are exposed. Today's MarbleRenderer::expose for ImageModel settings.
  [[nodiscard]] cv::Mat expose(const cv::Mat& light, std::int64_t frame) const;

  [[nodiscard]] const Rendering& rendering() const { return rendering_; }
  [[nodiscard]] const RayTable& rays() const { return rays_; }
  [[nodiscard]] const TableTexture& texture() const { return texture_; }
  [[nodiscard]] const DefocusBlur& defocus() const { return defocus_; }
  [[nodiscard]] const SensorModel& sensor() const { return sensor_; }
  [[nodiscard]] cv::Size size() const { return intrinsics_.size; }
  /// Pixels between the table's exact nodes (TableField).
  [[nodiscard]] int table_spacing() const { return spacing_; }
  /// The bare table's light for `camera` (its pose), CV_32F.
  [[nodiscard]] TableField table(const PinholeCamera& camera) const;

 private:
  void check_camera(const PinholeCamera& camera) const;
  [[nodiscard]] cv::Mat field_radiance(std::span<const Eigen::Vector2d> centres, double diameter,
                                       const PinholeCamera& camera) const;

  Rendering rendering_;
  Intrinsics intrinsics_;
  std::optional<MarbleRenderer> today_;  // settings that are exactly today's ImageModel
  int spacing_;
  int margin_;  // pixels beyond the image whose light a blur can bring in
  RayTable rays_;
  TableTexture texture_;
  DefocusBlur defocus_;
  SensorModel sensor_;
  Eigen::Matrix3d cached_rotation_;
  Eigen::Vector3d cached_translation_;
  std::optional<TableField> cached_table_;
};

}  // namespace neopipe::sim
