#pragma once
// What a few marbles do to one frame, in the patch of pixels around them and their shadows: every
// pixel's ray (RayTable) is cast against each marble and, where it meets the table, from there
// towards the light against each marble. Both tests give a smooth signed distance (mm: the ray's
// distance from the sphere's centre less its radius; the light ray's likewise; a disk's in the
// table plane), whose difference over the neighbouring pixels is its gradient, and the pixel's
// area on the inside of that straight edge (pixel_coverage, exact for a straight edge) is how much
// of the pixel the marble or the shadow covers: outlines area-sampled without supersampling.
//
// Marbles whose patches overlap are rendered together, so a marble hides the table (and the
// shadows on it) behind it and shadows its neighbours. The result is the change to the bare
// table's light (TableField): zero outside the marbles and their shadows, so patches add up, and
// blurring a patch alone equals blurring the frame.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <span>

#include "sim/frame_geometry.hpp"
#include "sim/ray_table.hpp"
#include "sim/rendering.hpp"
#include "sim/shading.hpp"
#include "sim/table_field.hpp"

namespace neopipe::sim {

/// What every patch of a frame shares.
struct PatchContext {
  const Rendering& rendering;
  const FrameGeometry& geometry;
  const RayTable& rays;
  const TableField& table;
  const std::optional<Shader>& shader;  ///< the light, if there is one
  double radius;                        ///< the marbles', mm
};

/// The change (gray levels) that marbles centred at `centres` (camera frame: spheres' centres, or
/// disks' centres on the table) make to the table's light over `rect` (pixels; the rays must reach
/// one pixel beyond it), into `out` (CV_32F, rect's size, e.g. a view of a larger patch).
void marble_patch(const PatchContext& context, std::span<const Eigen::Vector3d> centres, const cv::Rect& rect,
                  cv::Mat& out);

}  // namespace neopipe::sim
