#pragma once
// Where Qualnav's navigator gets its viewframes: the panoramic sensor's ring read by the engine's
// panorama graph (nav::PanoramaReader) and the compass, one viewframe per look (qualnav.md §2, §3).

#include <functional>
#include <vector>

#include "nav/common/compass.hpp"
#include "nav/common/panorama_reading.hpp"
#include "nav/qualnav/metric/viewframe.hpp"
#include "pipeline/io/frame_source.hpp"

namespace neopipe::nav::qualnav {

class ViewSource {
 public:
  virtual ~ViewSource() = default;
  /// A viewframe taken now, at the tool's pose.
  virtual Viewframe look() = 0;

 protected:
  ViewSource() = default;
  ViewSource(const ViewSource&) = default;
  ViewSource& operator=(const ViewSource&) = default;
};

/// The viewframe of one ring's sightings: bearings (degrees → rad), e = the sighting's bearing
/// error, range intervals [d̂ / f, f · d̂] around each range estimate (f = `interval_factor`: the
/// sensor's 1.5, or 1 + e for a configured range error e), compass bearing (degrees → rad).
Viewframe viewframe_from_sightings(const std::vector<PanoramaSighting>& sightings, double compass_deg,
                                   double interval_factor);

/// The ring through the panorama graph, and the compass. `distort`, when set, changes each look's
/// sightings before they become a viewframe (the rig puts a range error in there).
class RingViewSource final : public ViewSource {
 public:
  using Distortion = std::function<void(std::vector<PanoramaSighting>&)>;
  /// `camera` and `compass` must outlive the source.
  RingViewSource(pipeline::io::FrameSource& camera, Compass& compass, const PanoramaModel& model,
                 double interval_factor, Distortion distort = {});
  /// Throws std::runtime_error when the camera gives no frame.
  Viewframe look() override;
  [[nodiscard]] std::int64_t frames() const { return frames_; }

 private:
  pipeline::io::FrameSource& camera_;
  Compass& compass_;
  PanoramaReader reader_;
  double interval_factor_;
  Distortion distort_;
  std::int64_t frames_ = 0;
};

}  // namespace neopipe::nav::qualnav
