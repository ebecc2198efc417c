#pragma once
// What a navigator reads from the panoramic sensor's ring image (qualnav.md §2): one sighting per
// marble identity, with its bearing in the tool frame (no compass), an estimate of its range and an
// interval that holds the true range. The ring runs through the engine's built-in panorama graph
// (pipeline/builtin_graphs.hpp: blobs of equal value), so nothing here sees the truth.
//
// Per identity: id = value - 1; the blobs of one value are joined (a disc across the seam at
// column 0 / 3599 is two blobs; a half-hidden disc may be more), the bearing from their
// area-weighted centroid with columns unwrapped around the largest piece; ρ̂ = 0.1°·√(area/π),
// d̂ = r_m / sin ρ̂, range interval [d̂/1.5, 1.5·d̂]; angular error e = 0.2° + the configured noise.
// A disc partly hidden by a nearer one shows less area, so its d̂ is too large (it is farther than
// the one hiding it in any case) and its centroid is pulled away from the hidden side: `partial`
// flags sightings that may be so.

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "kernels/blobs.hpp"
#include "pipeline/inline_runner.hpp"

namespace neopipe::nav {

/// The ring's geometry, as sim/panorama.hpp draws it (a test holds the two to each other).
inline constexpr int kPanoramaWidth = 3600;
inline constexpr double kPanoramaDegreesPerPixel = 0.1;
inline constexpr double kPanoramaRangeFactor = 1.5;          ///< the interval [d̂ / f, f · d̂]
inline constexpr double kPanoramaBaseBearingErrorDeg = 0.2;  ///< e without configured noise

/// What a navigator may know about its sensor.
struct PanoramaModel {
  double marble_radius_mm = 2.5;  ///< r_m
  double bearing_noise_deg = 0;   ///< the configured noise of the sensor's bearings
};

struct PanoramaSighting {
  std::uint32_t id = 0;
  double bearing_deg = 0;         ///< [0, 360), counter-clockwise from the tool's +x axis
  double bearing_error_deg = 0;   ///< e
  double angular_radius_deg = 0;  ///< ρ̂
  double range_mm = 0;            ///< d̂
  double range_lo_mm = 0;         ///< d̂ / 1.5
  double range_hi_mm = 0;         ///< 1.5 · d̂
  std::int64_t area_px = 0;       ///< of all its pieces
  int pieces = 1;                 ///< blobs joined (2 for a disc across the seam)
  /// Its blobs touch the box of a nearer (larger) disc's, or it is cut into pieces other than by
  /// the seam: it may be partly hidden, its range too large and its bearing pulled aside.
  bool partial = false;
};

/// The sightings in a ring image's blob table (the panorama graph's output), in id order. Blobs of
/// value <= 0 are ignored.
std::vector<PanoramaSighting> sightings_from_blobs(const std::vector<kernels::Blob>& blobs, const PanoramaModel& model);

/// Runs the engine's panorama graph on ring images one at a time on the calling thread.
class PanoramaReader {
 public:
  explicit PanoramaReader(const PanoramaModel& model);
  /// `ring`: CV_16SC1 (the sensor's frame). Throws std::invalid_argument for another type, or a
  /// size other than the first ring's.
  std::vector<PanoramaSighting> read(const cv::Mat& ring);
  [[nodiscard]] const PanoramaModel& model() const { return model_; }

 private:
  PanoramaModel model_;
  pipeline::InlineRunner runner_;
};

/// The k sightings of smallest range estimate, nearest first (equal estimates in id order); all of
/// them when there are fewer. QRM orders the ranges of the k = 18 nearest (qrm.md §9).
std::vector<PanoramaSighting> nearest_by_range(std::vector<PanoramaSighting> sightings, std::size_t k);

}  // namespace neopipe::nav
