// The navigator's eye: the engine's built-in blob graph run on one onboard frame at a time, its
// centroids turned into window coordinates. The navigator needs each sighting before it can decide
// its next move, so there is never a second frame to overlap with: the graph runs inline on the
// calling thread (pipeline::InlineRunner), without the executor's worker threads (and without the
// process-wide thread limit it sets while it lives).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>

#include "nav/navigator/navigator.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::nav::navigator {
namespace {

pipeline::CompiledGraph gray_blob_graph() {
  pipeline::BlobGraphOptions options;
  options.source = pipeline::PortType::gray8;
  pipeline::CompiledGraph graph = pipeline::compile(pipeline::blob_graph(options), pipeline::standard_kernels());
  // Each sighting stands alone: a delayed edge would make a look depend on the one before.
  if (graph.has_delays()) throw std::logic_error("the navigator's blob graph must not have delays");
  return graph;
}

// The workspace's gray level: the median of a sparse grid of pixels. Marbles cover a small part of
// any window, so the median is the bare plane whatever the illumination gradient.
int background_level(const cv::Mat& gray) {
  std::array<int, 256> histogram{};
  int count = 0;
  constexpr int stride = 7;
  for (int y = stride / 2; y < gray.rows; y += stride) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    for (int x = stride / 2; x < gray.cols; x += stride) {
      ++histogram[row[x]];
      ++count;
    }
  }
  int seen = 0;
  for (int v = 0; v < 256; ++v) {
    seen += histogram[static_cast<std::size_t>(v)];
    if (2 * seen >= count) return v;
  }
  return 255;
}

// A disk of radius r whose centre lies at c from a border line (negative: beyond it) shows the part
// on this side; its centroid lies at centroid_of_cut(c, r) from the line. Monotonic in c.
double centroid_of_cut(double c, double r) {
  const double h = std::clamp(c, -r, r);
  // The segment beyond the line: area and the distance of its centroid from the disk's centre.
  const double cut_area = r * r * std::acos(h / r) - h * std::sqrt(r * r - h * h);
  const double kept = std::numbers::pi * r * r - cut_area;
  if (kept <= 1e-12) return 0;
  const double cut_arm = cut_area > 1e-12 ? (2.0 / 3.0) * std::pow(r * r - h * h, 1.5) / cut_area : 0.0;
  return c + cut_area * cut_arm / kept;
}

// The centre distance c (from the border, px) of a marble whose cut blob has its centroid at
// `centroid` from the border: centroid_of_cut inverted by bisection.
double uncut_centre(double centroid, double r) {
  double lo = -r;
  double hi = std::max(centroid, r);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (centroid_of_cut(mid, r) < centroid ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// A disk of radius r centred at c (px, from a corner of the image along the two borders that meet
// there; negative beyond them) shows the part inside both: its area and centroid, by integrating
// its chords column by column.
struct Cut {
  double area = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};
Cut corner_cut(const Eigen::Vector2d& c, double r) {
  constexpr int columns = 128;
  const double x0 = std::max(0.0, c.x() - r);
  const double x1 = c.x() + r;
  Cut cut;
  if (x1 <= x0) return cut;
  const double dx = (x1 - x0) / columns;
  double sx = 0;
  double sy = 0;
  for (int i = 0; i < columns; ++i) {
    const double x = x0 + (i + 0.5) * dx;
    const double h = std::sqrt(std::max(0.0, r * r - (x - c.x()) * (x - c.x())));
    const double y0 = std::max(0.0, c.y() - h);
    const double y1 = c.y() + h;
    if (y1 <= y0) continue;
    const double len = (y1 - y0) * dx;
    cut.area += len;
    sx += x * len;
    sy += 0.5 * (y0 + y1) * len;
  }
  if (cut.area > 0) cut.centroid = {sx / cut.area, sy / cut.area};
  return cut;
}

// The centre of a marble whose blob, cut by two borders at a corner, has its centroid at `centroid`
// (px from that corner along both borders). The centroid moves with the centre, never faster, so
// stepping the centre by the centroid's miss converges (slowly only for deep caps, which matter
// little); it starts from the one-border answers, right when the two cuts barely interact.
Eigen::Vector2d uncut_corner_centre(const Eigen::Vector2d& centroid, double r) {
  Eigen::Vector2d c(uncut_centre(centroid.x(), r), uncut_centre(centroid.y(), r));
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Cut cut = corner_cut(c, r);
    if (cut.area <= 0) break;
    const Eigen::Vector2d miss = centroid - cut.centroid;
    c = (c + miss).cwiseMax(-r).cwiseMin(centroid);  // the cuts only ever pull the centroid inward
    if (miss.norm() < 1e-3) break;
  }
  return c;
}

}  // namespace

struct Eye::Impl {
  Impl(pipeline::io::FrameSource& camera, const NavigatorConfig& navigator)
      : source(camera),
        config(navigator),
        runner(gray_blob_graph()),
        blobs(*runner.graph().find_output(pipeline::PortType::blobs)) {
    blob_radius_px = 0.5 * config.camera.object_diameter / config.window.side * config.camera.side_px;
  }

  const pipeline::BlobList& run(const cv::Mat& frame) {
    if (frame.type() != CV_8UC1) throw std::runtime_error("the navigator's eye takes gray frames (CV_8UC1)");
    return std::get<pipeline::BlobList>(runner.run(frame).at(blobs));
  }

  pipeline::io::FrameSource& source;
  NavigatorConfig config;
  pipeline::InlineRunner runner;
  std::size_t blobs;
  pipeline::io::SourceFrame last;
  std::int64_t frames = 0;
  double blob_radius_px = 0;  // a whole marble's blob radius at the current threshold
};

Eye::Eye(pipeline::io::FrameSource& source, const NavigatorConfig& config)
    : impl_(std::make_unique<Impl>(source, config)) {}
Eye::~Eye() = default;

const pipeline::io::SourceFrame& Eye::last_frame() const {
  return impl_->last;
}

Sighting Eye::look() {
  Impl& eye = *impl_;
  std::optional<pipeline::io::SourceFrame> frame = eye.source.next();
  if (!frame) throw std::runtime_error("the onboard camera (" + eye.source.description() + ") has no more frames");
  eye.last = std::move(*frame);
  const cv::Mat& image = eye.last.image;
  const pipeline::BlobList& blobs = eye.run(image);

  const double a = eye.config.window.side;
  const double mm_per_px_x = a / image.cols;
  const double mm_per_px_y = a / image.rows;
  const int background = background_level(image);

  // Marbles: blobs big enough not to be sensor noise and bright at their centroid (on a view with no
  // marble, Otsu's threshold splits the noise into blobs that are neither).
  const auto marble = [&](const kernels::Blob& b) {
    if (b.area < eye.config.camera.min_blob_area) return false;
    const int u = std::clamp(static_cast<int>(b.cx), 0, image.cols - 1);
    const int v = std::clamp(static_cast<int>(b.cy), 0, image.rows - 1);
    return image.at<std::uint8_t>(v, u) >= background + eye.config.camera.min_contrast;
  };
  // The radius a marble's blob has at this frame's threshold, from the marbles the border does not
  // cut and of about a marble's size (kept from earlier frames when there are none).
  const double nominal = 0.5 * eye.config.camera.object_diameter / mm_per_px_x;
  double radii = 0;
  int whole = 0;
  for (const kernels::Blob& b : blobs) {
    const bool cut = b.x0 == 0 || b.y0 == 0 || b.x0 + b.width == image.cols || b.y0 + b.height == image.rows;
    const double radius = std::sqrt(static_cast<double>(b.area) / std::numbers::pi);
    if (!cut && marble(b) && radius > 0.7 * nominal && radius < 1.3 * nominal) {
      radii += radius;
      ++whole;
    }
  }
  if (whole > 0) eye.blob_radius_px = radii / whole;

  Sighting s;
  s.frame = eye.frames++;
  for (const kernels::Blob& b : blobs) {
    if (!marble(b)) continue;
    // Pixel centres are at (u + 0.5, v + 0.5). A blob cut by a border is the part of its marble's
    // disk on this side: its centroid is pulled inward, by an amount known for a disk cut by a line.
    double cx = b.cx + 0.5;
    double cy = b.cy + 0.5;
    const double r = eye.blob_radius_px;
    const bool west = b.x0 == 0;
    const bool east = b.x0 + b.width == image.cols;
    const bool north = b.y0 == 0;
    const bool south = b.y0 + b.height == image.rows;
    const bool cut_x = west != east;
    const bool cut_y = north != south;
    if (cut_x && cut_y) {
      // Cut at a corner: both borders pull the centroid, so both are undone at once.
      const Eigen::Vector2d from_corner(west ? cx : image.cols - cx, north ? cy : image.rows - cy);
      const Eigen::Vector2d c = uncut_corner_centre(from_corner, r);
      cx = west ? c.x() : image.cols - c.x();
      cy = north ? c.y() : image.rows - c.y();
    } else if (cut_x) {
      cx = west ? uncut_centre(cx, r) : image.cols - uncut_centre(image.cols - cx, r);
    } else if (cut_y) {
      cy = north ? uncut_centre(cy, r) : image.rows - uncut_centre(image.rows - cy, r);
    }
    const Eigen::Vector2d p(cx * mm_per_px_x, a - cy * mm_per_px_y);
    // Visible means the centre strictly inside the window (park-kender.md §2), as the map-maker
    // assumed: a cap whose marble's centre lies outside is not an object in view.
    if (p.x() > 0 && p.x() < a && p.y() > 0 && p.y() < a) {
      s.objects.push_back(p);
    } else {
      s.partial.push_back(p);
    }
  }
  return s;
}

}  // namespace neopipe::nav::navigator
