#pragma once
// The standard normal distribution function, shared by the reliability models.

#include <cmath>
#include <numbers>

namespace neopipe::nav::mapmaker {

inline double normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

}  // namespace neopipe::nav::mapmaker
