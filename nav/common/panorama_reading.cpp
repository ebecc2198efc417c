#include "nav/common/panorama_reading.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <variant>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::nav {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// dx wrapped into [-width/2, width/2).
double wrap_columns(double dx) {
  constexpr double w = kPanoramaWidth;
  return dx - w * std::floor((dx + w / 2) / w);
}

// Whether two boxes, each grown by a pixel, meet; columns wrap around the ring.
bool boxes_touch(const kernels::Blob& a, const kernels::Blob& b) {
  if (a.y0 > b.y0 + b.height || b.y0 > a.y0 + a.height) return false;
  for (const int shift : {-kPanoramaWidth, 0, kPanoramaWidth}) {
    const int bx0 = b.x0 + shift;
    if (a.x0 <= bx0 + b.width && bx0 <= a.x0 + a.width) return true;
  }
  return false;
}

bool on_seam(const kernels::Blob& b) {
  return b.x0 == 0 || b.x0 + b.width == kPanoramaWidth;
}

pipeline::CompiledGraph panorama_graph() {
  pipeline::CompiledGraph graph = pipeline::compile(pipeline::panorama_graph(), pipeline::standard_kernels());
  // Each look stands alone: a delayed edge would make a reading depend on the one before.
  if (graph.has_delays()) throw std::logic_error("the panorama graph must not have delays");
  return graph;
}

}  // namespace

std::vector<PanoramaSighting> sightings_from_blobs(const std::vector<kernels::Blob>& blobs,
                                                   const PanoramaModel& model) {
  std::map<int, std::vector<const kernels::Blob*>> by_value;  // in id order
  for (const auto& b : blobs) {
    if (b.value > 0 && b.area > 0) by_value[b.value].push_back(&b);
  }
  std::vector<PanoramaSighting> out;
  out.reserve(by_value.size());
  std::vector<const std::vector<const kernels::Blob*>*> pieces_of;
  for (const auto& [value, pieces] : by_value) {
    PanoramaSighting s;
    s.id = static_cast<std::uint32_t>(value - 1);
    s.pieces = static_cast<int>(pieces.size());
    // The pieces' centroids unwrapped around the largest one's: exact for a disc cut by the seam
    // (the centroid of the whole disc), unlike a mean of unit vectors, which pulls it inward.
    const kernels::Blob* largest = *std::max_element(
        pieces.begin(), pieces.end(), [](const kernels::Blob* a, const kernels::Blob* b) { return a->area < b->area; });
    double moment = 0;
    for (const auto* p : pieces) {
      s.area_px += p->area;
      moment += static_cast<double>(p->area) * wrap_columns(p->cx - largest->cx);
    }
    const double column = largest->cx + moment / static_cast<double>(s.area_px);
    double bearing = std::fmod((column + 0.5) * kPanoramaDegreesPerPixel, 360.0);
    if (bearing < 0) bearing += 360.0;
    s.bearing_deg = bearing >= 360.0 ? 0.0 : bearing;
    s.bearing_error_deg = kPanoramaBaseBearingErrorDeg + model.bearing_noise_deg;
    s.angular_radius_deg =
        std::min(90.0, kPanoramaDegreesPerPixel * std::sqrt(static_cast<double>(s.area_px) / std::numbers::pi));
    s.range_mm = model.marble_radius_mm / std::sin(s.angular_radius_deg * kDegree);
    s.range_lo_mm = s.range_mm / kPanoramaRangeFactor;
    s.range_hi_mm = s.range_mm * kPanoramaRangeFactor;
    const bool seam_pair = pieces.size() == 2 && on_seam(*pieces[0]) && on_seam(*pieces[1]);
    s.partial = pieces.size() > 2 || (pieces.size() == 2 && !seam_pair);
    // A whole disc is as wide as it is tall (to a pixel); a nearer disc, centred on the same row,
    // takes a side of it and so some of its width first.
    int width = 0;
    int height = 0;
    for (const auto* p : pieces) {
      width += p->width;
      height = std::max(height, p->height);
    }
    s.partial = s.partial || width + 1 < height;
    out.push_back(s);
    pieces_of.push_back(&pieces);
  }
  // A disc can be hidden only by a nearer one, which is larger; but that one may be partly hidden
  // too, so "larger" is judged by visible area or height, whichever says so.
  const auto height = [&](std::size_t i) {
    int h = 0;
    for (const auto* p : *pieces_of[i]) h = std::max(h, p->height);
    return h;
  };
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (std::size_t j = 0; j < out.size() && !out[i].partial; ++j) {
      if (j == i || (out[j].area_px <= out[i].area_px && height(j) <= height(i))) continue;
      for (const auto* a : *pieces_of[i]) {
        for (const auto* b : *pieces_of[j]) out[i].partial = out[i].partial || boxes_touch(*a, *b);
      }
    }
  }
  return out;
}

PanoramaReader::PanoramaReader(const PanoramaModel& model) : model_(model), runner_(panorama_graph()) {
  if (!(model.marble_radius_mm > 0) || !(model.bearing_noise_deg >= 0)) {
    throw std::invalid_argument("panorama reader: the marble radius must be > 0 and the bearing noise >= 0");
  }
}

std::vector<PanoramaSighting> PanoramaReader::read(const cv::Mat& ring) {
  const auto& outputs = runner_.run(ring);
  return sightings_from_blobs(std::get<pipeline::BlobList>(outputs.at(0)), model_);
}

std::vector<PanoramaSighting> nearest_by_range(std::vector<PanoramaSighting> sightings, std::size_t k) {
  std::sort(sightings.begin(), sightings.end(), [](const PanoramaSighting& a, const PanoramaSighting& b) {
    return a.range_mm != b.range_mm ? a.range_mm < b.range_mm : a.id < b.id;
  });
  if (sightings.size() > k) sightings.resize(k);
  return sightings;
}

}  // namespace neopipe::nav
