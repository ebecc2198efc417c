#include "sim/range_ring.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace neopipe::sim {
namespace {

constexpr double kRingDegree = std::numbers::pi / 180;

double wrap_ring_degrees(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}

void check_ring_settings(const RangeRingSettings& s) {
  if (!(s.range_mm > 0) || !std::isfinite(s.range_mm)) {
    throw std::invalid_argument("range ring: the range must be a positive number of mm");
  }
  if (!(s.relative_error >= 0 && s.relative_error < 1)) {
    throw std::invalid_argument("range ring: the relative error must lie in [0, 1)");
  }
  if (!(s.compass_sigma_deg >= 0) || !std::isfinite(s.compass_sigma_deg)) {
    throw std::invalid_argument("range ring: the compass sigma must be >= 0 degrees");
  }
}

}  // namespace

int range_sector(double bearing_deg) {
  const double shifted = wrap_ring_degrees(bearing_deg + kRangeSectorDeg / 2);
  const int k = static_cast<int>(std::floor(shifted / kRangeSectorDeg));
  return k >= kRangeSectors ? 0 : k;
}

std::array<double, kRangeSectors> true_ranges(const World& world, const Pose2& tool, double range_mm) {
  std::array<double, kRangeSectors> out{};
  const double c = std::cos(tool.theta);
  const double s = std::sin(tool.theta);
  const double radius = world.marble_diameter / 2;
  for (const Eigen::Vector2d& m : world.objects) {
    const Eigen::Vector2d q = m - Eigen::Vector2d(tool.x, tool.y);
    const double gap = q.norm() - radius;
    if (gap > range_mm || gap <= 0) continue;
    const double x = c * q.x() + s * q.y();
    const double y = -s * q.x() + c * q.y();
    double& slot = out[static_cast<std::size_t>(range_sector(std::atan2(y, x) / kRingDegree))];
    if (slot == 0 || gap < slot) slot = gap;
  }
  return out;
}

cv::Mat range_ring_frame(const World& world, const Pose2& tool, const RangeRingSettings& settings, Random* noise) {
  check_ring_settings(settings);
  const std::array<double, kRangeSectors> ranges = true_ranges(world, tool, settings.range_mm);
  cv::Mat frame(1, kRangeSectors, CV_32FC1, cv::Scalar(0));
  for (int k = 0; k < kRangeSectors; ++k) {
    double r = ranges[static_cast<std::size_t>(k)];
    if (r > 0 && noise != nullptr && settings.relative_error > 0) {
      r *= 1 + noise->uniform(-settings.relative_error, settings.relative_error);
    }
    frame.at<float>(0, k) = static_cast<float>(r);
  }
  return frame;
}

RangeRingSensor::RangeRingSensor(World world, const RangeRingSettings& settings)
    : world_(std::move(world)), settings_(settings), range_noise_(settings.seed), compass_noise_(~settings.seed) {
  check_ring_settings(settings_);
}

cv::Mat RangeRingSensor::frame(const Pose2& tool) {
  return range_ring_frame(world_, tool, settings_, &range_noise_);
}

double RangeRingSensor::compass_deg(const Pose2& tool) {
  return wrap_ring_degrees(tool.theta / kRingDegree + compass_noise_.normal(0, settings_.compass_sigma_deg));
}

namespace {

class RangeRingSource final : public pipeline::io::FrameSource {
 public:
  RangeRingSource(RangeRingSensor& sensor, std::function<Pose2()> where) : sensor_(sensor), where_(std::move(where)) {}

  std::optional<pipeline::io::SourceFrame> next() override {
    pipeline::io::SourceFrame f;
    f.index = index_++;
    f.image = sensor_.frame(where_());
    return f;
  }
  [[nodiscard]] std::string description() const override { return "range ring"; }
  [[nodiscard]] double fps() const override { return 0; }
  [[nodiscard]] std::optional<std::int64_t> frame_count() const override { return std::nullopt; }

 private:
  RangeRingSensor& sensor_;
  std::function<Pose2()> where_;
  std::int64_t index_ = 0;
};

}  // namespace

std::unique_ptr<pipeline::io::FrameSource> range_ring_camera_source(RangeRingSensor& sensor,
                                                                    std::function<Pose2()> where) {
  return std::make_unique<RangeRingSource>(sensor, std::move(where));
}

}  // namespace neopipe::sim
