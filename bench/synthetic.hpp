#pragma once
// Generated benchmark frames, so every machine measures the same pictures.

#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace neopipe::bench {

/// About `count` small bright, smoothly shaded, anti-aliased disks (radius `radius`, or when that is
/// 0 min(w, h) / 80, at least 3 px) on a dark background with a gentle gradient and Gaussian noise:
/// the simulator's marbles. Disks do not overlap (centres more than 2 radius + 4 apart); where fewer
/// than `count` fit, the frame has fewer. Foreground is value > dots_threshold.
cv::Mat make_dots_frame(cv::Size size, int count, std::uint64_t seed, double radius = 0);
inline constexpr int dots_threshold = 128;

/// Smoothed noise: thresholded at its mean it falls into many large irregular components.
cv::Mat make_dense_frame(cv::Size size, std::uint64_t seed);
/// The frame's mean, rounded down: the dense case's threshold.
int dense_threshold(const cv::Mat& frame);

}  // namespace neopipe::bench
