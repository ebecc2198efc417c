#include "pipeline/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace neopipe::pipeline {
namespace {
constexpr double kLowest = 1e-7;  // seconds; anything faster lands in bucket 0
constexpr int kPerOctave = 256;   // bucket width 2^(1/256) - 1 = 0.27 %
constexpr int kOctaves = 37;      // 1e-7 * 2^37 s is about 3.8 hours
constexpr int kBuckets = kPerOctave * kOctaves;

int bucket_of(double s) {
  if (!(s > kLowest)) return 0;
  const int b = static_cast<int>(std::floor(std::log2(s / kLowest) * kPerOctave));
  return std::min(b, kBuckets - 1);
}

double centre_of(int b) {
  return kLowest * std::exp2((b + 0.5) / kPerOctave);
}
}  // namespace

LatencyHistogram::LatencyHistogram() : buckets_(kBuckets, 0) {}

void LatencyHistogram::add(double seconds) {
  if (!(seconds > 0)) seconds = 0;
  ++buckets_[static_cast<size_t>(bucket_of(seconds))];
  min_ = count_ == 0 ? seconds : std::min(min_, seconds);
  max_ = count_ == 0 ? seconds : std::max(max_, seconds);
  ++count_;
}

double LatencyHistogram::quantile(double q) const {
  if (count_ == 0) return 0;
  const auto rank =
      std::clamp(static_cast<std::int64_t>(std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(count_))),
                 std::int64_t{1}, count_);
  std::int64_t seen = 0;
  for (int b = 0; b < kBuckets; ++b) {
    seen += static_cast<std::int64_t>(buckets_[static_cast<size_t>(b)]);
    if (seen >= rank) return std::clamp(centre_of(b), min_, max_);
  }
  return max_;
}

}  // namespace neopipe::pipeline
