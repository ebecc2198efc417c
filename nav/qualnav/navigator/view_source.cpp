#include "nav/qualnav/navigator/view_source.hpp"

#include <numbers>
#include <stdexcept>
#include <utility>

namespace neopipe::nav::qualnav {

Viewframe viewframe_from_sightings(const std::vector<PanoramaSighting>& sightings, double compass_deg,
                                   double interval_factor) {
  constexpr double kRad = std::numbers::pi / 180;
  std::vector<ViewedLandmark> v;
  v.reserve(sightings.size());
  for (const PanoramaSighting& s : sightings) {
    v.push_back({s.id, s.bearing_deg * kRad, s.bearing_error_deg * kRad, s.range_mm, s.range_mm / interval_factor,
                 s.range_mm * interval_factor});
  }
  return make_viewframe(std::move(v), compass_deg * kRad);
}

RingViewSource::RingViewSource(pipeline::io::FrameSource& camera, Compass& compass, const PanoramaModel& model,
                               double interval_factor, Distortion distort)
    : camera_(camera),
      compass_(compass),
      reader_(model),
      interval_factor_(interval_factor),
      distort_(std::move(distort)) {}

Viewframe RingViewSource::look() {
  const auto frame = camera_.next();
  if (!frame) throw std::runtime_error("the panoramic camera gave no frame");
  ++frames_;
  std::vector<PanoramaSighting> sightings = reader_.read(frame->image);
  if (distort_) distort_(sightings);
  return viewframe_from_sightings(sightings, compass_.read().heading_deg, interval_factor_);
}

}  // namespace neopipe::nav::qualnav
