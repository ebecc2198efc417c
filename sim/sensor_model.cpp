#include "sim/sensor_model.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace neopipe::sim {

SensorModel::SensorModel(const Sensor& s, cv::Size size)
    : sensor_(s), size_(size), gain_(size, CV_32F), noise_(s.seed) {
  if (size.width > GaussianNoise::kRowMax) throw std::invalid_argument("image wider than the noise table's rows");
  const double a = s.gradient_angle_deg * std::numbers::pi / 180;
  const double half_diagonal = std::hypot(size.width, size.height) / 2;
  const double cx = (size.width - 1) / 2.0;
  const double cy = (size.height - 1) / 2.0;
  Random prnu(s.seed ^ 0x70726E75ULL);  // "prnu": fixed per camera and seed, apart from the noise
  for (int y = 0; y < size.height; ++y) {
    auto* g = gain_.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const double along = ((x - cx) * std::cos(a) + (y - cy) * std::sin(a)) / half_diagonal;
      const double rho = std::hypot(x - cx, y - cy) / half_diagonal;
      const double pixel = s.prnu > 0 ? 1 + s.prnu * prnu.normal() : 1.0;
      g[x] = static_cast<float>((1 + s.gradient * along) * (1 - s.vignetting * rho * rho) * pixel);
    }
  }
}

cv::Mat SensorModel::expose(const cv::Mat& even, const cv::Mat& odd, std::int64_t frame) const {
  if (even.size() != size_ || odd.size() != size_ || even.type() != CV_32F || odd.type() != CV_32F) {
    throw std::invalid_argument("sensor: light image of the wrong size or type");
  }
  cv::Mat out(size_, CV_8U);
  Random rows = frame_random(sensor_.seed, frame);
  const auto read2 = static_cast<float>(sensor_.read_noise * sensor_.read_noise);
  const auto shot = static_cast<float>(sensor_.full_well ? 255 / *sensor_.full_well : 0.0);
  const int w = size_.width;
  for (int y = 0; y < size_.height; ++y) {
    const auto* light = (y % 2 == 0 ? even : odd).ptr<float>(y);
    const auto* g = gain_.ptr<float>(y);
    const float* n = noise_.row(rows, w).data();
    auto* o = out.ptr<std::uint8_t>(y);
    // Plain arithmetic the compiler vectorises (this file is built without errno for sqrt).
    for (int x = 0; x < w; ++x) {
      const float signal = std::max(0.0F, g[x] * light[x]);
      float v = signal + std::sqrt(read2 + shot * signal) * n[x];
      v = std::min(std::max(v, 0.0F), 255.0F);
      o[x] = static_cast<std::uint8_t>(
          v + 0.5F);  // NOLINT(bugprone-incorrect-roundings): v >= 0, and lround is slower here
    }
  }
  return out;
}

}  // namespace neopipe::sim
