#include "sim/panorama.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace neopipe::sim {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

double wrap_degrees(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;  // fmod of a tiny negative may round up to 360
}

void check_settings(const World& world, const PanoramaSettings& s) {
  if (world.objects.size() > kRingMaxMarbles) {
    throw std::invalid_argument("panorama: " + std::to_string(world.objects.size()) +
                                " marbles, but the ring image labels at most 32767 (values id + 1 in 16 bits)");
  }
  if (!(s.range_mm > 0) || !std::isfinite(s.range_mm)) {
    throw std::invalid_argument("panorama: the range R_s must be a positive number of mm");
  }
  if (!(s.bearing_noise_deg >= 0) || !std::isfinite(s.bearing_noise_deg)) {
    throw std::invalid_argument("panorama: the bearing noise must be >= 0 degrees");
  }
  if (!(s.compass_sigma_deg >= 0) || !std::isfinite(s.compass_sigma_deg)) {
    throw std::invalid_argument("panorama: the compass sigma must be >= 0 degrees");
  }
}

// Fills the disc of radius r px centred at column uc, row kRingMiddleRow with `value`: every pixel
// whose centre lies within r, columns taken modulo the ring's width.
void fill_disc(cv::Mat& ring, double uc, double r, std::int16_t value) {
  const double vc = kRingMiddleRow;
  const int v0 = std::max(0, static_cast<int>(std::ceil(vc - r)));
  const int v1 = std::min(kRingHeight - 1, static_cast<int>(std::floor(vc + r)));
  for (int v = v0; v <= v1; ++v) {
    const double dv = v - vc;
    const double h = std::sqrt(std::max(0.0, r * r - dv * dv));
    const int u0 = static_cast<int>(std::ceil(uc - h));
    int u1 = static_cast<int>(std::floor(uc + h));
    if (u1 < u0) continue;
    // A disc is at most 180° wide (r <= 900 px), so it wraps at most once.
    u1 = std::min(u1, u0 + kRingWidth - 1);
    auto* row = ring.ptr<std::int16_t>(v);
    const int start = ((u0 % kRingWidth) + kRingWidth) % kRingWidth;
    const int count = u1 - u0 + 1;
    const int first = std::min(count, kRingWidth - start);
    std::fill(row + start, row + start + first, value);
    std::fill(row, row + (count - first), value);
  }
}

}  // namespace

double ring_column(double bearing_deg) {
  return bearing_deg / kRingDegreesPerPixel - 0.5;
}

double ring_bearing_deg(double column) {
  return wrap_degrees((column + 0.5) * kRingDegreesPerPixel);
}

std::vector<MarbleInView> marbles_in_view(const World& world, const Pose2& tool, double range_mm) {
  // Every marble is tested: a few hundred distances cost microseconds, less than the image's clear,
  // and a grid cell of R_s would span most worlds anyway.
  const double c = std::cos(tool.theta);
  const double s = std::sin(tool.theta);
  const double r = world.marble_diameter / 2;
  std::vector<MarbleInView> out;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const Eigen::Vector2d q = world.objects[i] - Eigen::Vector2d(tool.x, tool.y);
    const double d = q.norm();
    if (d > range_mm || d <= r) continue;
    const double x = c * q.x() + s * q.y();
    const double y = -s * q.x() + c * q.y();
    out.push_back(
        {static_cast<std::uint32_t>(i), wrap_degrees(std::atan2(y, x) / kDegree), d, std::asin(r / d) / kDegree});
  }
  return out;
}

Ring render_ring(const World& world, const Pose2& tool, const PanoramaSettings& settings, Random* noise) {
  check_settings(world, settings);
  Ring ring;
  ring.image = cv::Mat(kRingHeight, kRingWidth, CV_16SC1, cv::Scalar(0));
  const double r_m = world.marble_diameter / 2;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if ((world.objects[i] - Eigen::Vector2d(tool.x, tool.y)).norm() <= r_m) {
      ring.inside.push_back(static_cast<std::uint32_t>(i));
    }
  }
  std::vector<MarbleInView> marbles = marbles_in_view(world, tool, settings.range_mm);
  if (noise != nullptr && settings.bearing_noise_deg > 0) {
    for (auto& m : marbles) m.bearing_deg = wrap_degrees(m.bearing_deg + noise->normal(0, settings.bearing_noise_deg));
  }
  // Farthest first, so nearer discs cover them; equal distances in id order, for determinism.
  std::sort(marbles.begin(), marbles.end(), [](const MarbleInView& a, const MarbleInView& b) {
    return a.distance_mm != b.distance_mm ? a.distance_mm > b.distance_mm : a.id < b.id;
  });
  for (const auto& m : marbles) {
    fill_disc(ring.image, ring_column(m.bearing_deg), m.angular_radius_deg / kRingDegreesPerPixel,
              static_cast<std::int16_t>(m.id + 1));
  }
  ring.discs = static_cast<int>(marbles.size());
  return ring;
}

std::optional<NearestSurface> nearest_surface(const World& world, const Eigen::Vector2d& point) {
  if (world.objects.empty()) return std::nullopt;
  NearestSurface best{0, std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const double gap = (world.objects[i] - point).norm() - world.marble_diameter / 2;
    if (gap < best.gap_mm) best = {static_cast<std::uint32_t>(i), gap};
  }
  return best;
}

bool keeps_clear(const World& world, const Eigen::Vector2d& point, double min_gap_mm) {
  const auto nearest = nearest_surface(world, point);
  return !nearest || nearest->gap_mm >= min_gap_mm;
}

PanoramicSensor::PanoramicSensor(World world, const PanoramaSettings& settings)
    : world_(std::move(world)), settings_(settings), ring_noise_(settings.seed), compass_noise_(~settings.seed) {
  check_settings(world_, settings_);
}

Ring PanoramicSensor::ring(const Pose2& tool) {
  return render_ring(world_, tool, settings_, &ring_noise_);
}

double PanoramicSensor::compass_deg(const Pose2& tool) {
  return wrap_degrees(tool.theta / kDegree + compass_noise_.normal(0, settings_.compass_sigma_deg));
}

namespace {

class PanoramaSource final : public pipeline::io::FrameSource {
 public:
  PanoramaSource(PanoramicSensor& sensor, std::function<Pose2()> where) : sensor_(sensor), where_(std::move(where)) {}

  std::optional<pipeline::io::SourceFrame> next() override {
    pipeline::io::SourceFrame f;
    f.index = index_++;
    f.image = sensor_.ring(where_()).image;
    return f;
  }
  [[nodiscard]] std::string description() const override { return "panoramic sensor"; }
  [[nodiscard]] double fps() const override { return 0; }
  [[nodiscard]] std::optional<std::int64_t> frame_count() const override { return std::nullopt; }

 private:
  PanoramicSensor& sensor_;
  std::function<Pose2()> where_;
  std::int64_t index_ = 0;
};

}  // namespace

std::unique_ptr<pipeline::io::FrameSource> panoramic_camera_source(PanoramicSensor& sensor,
                                                                   std::function<Pose2()> where) {
  return std::make_unique<PanoramaSource>(sensor, std::move(where));
}

}  // namespace neopipe::sim
