#pragma once
// The sensor: light (gray levels) to 8-bit pixels. Per pixel a fixed gain (vignetting, PRNU and the
// ImageModel's illumination gradient, precomputed per camera), then photon shot noise (variance
// proportional to the signal: gray x 255 / full well, in gray levels squared) and read noise
// (Gaussian) as one Gaussian of their summed variance, drawn from the noise table
// (sim/gaussian_noise.hpp), and rounding to 8 bits. Interlaced frames take their even rows from one
// light image and their odd rows from another.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "sim/gaussian_noise.hpp"
#include "sim/rendering.hpp"

namespace neopipe::sim {

class SensorModel {
 public:
  SensorModel(const Sensor& sensor, cv::Size size);

  /// The 8-bit frame `frame` of light `even` (CV_32F, this size) and, for its odd rows, `odd`
  /// (pass `even` again for a progressive frame).
  [[nodiscard]] cv::Mat expose(const cv::Mat& even, const cv::Mat& odd, std::int64_t frame) const;
  /// The fixed gain per pixel (CV_32F).
  [[nodiscard]] const cv::Mat& gain() const { return gain_; }

 private:
  Sensor sensor_;
  cv::Size size_;
  cv::Mat gain_;
  GaussianNoise noise_;
};

}  // namespace neopipe::sim
