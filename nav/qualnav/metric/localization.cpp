#include "nav/qualnav/metric/localization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace neopipe::nav::qualnav {
namespace {

using Eigen::Vector2d;

// One landmark of the frame as the constraints use it.
struct PlacedLandmark {
  Vector2d at;
  double lo = 0;
  double hi = 0;
  double bearing = 0;
  double error = 0;
};

// The signed counter-clockwise angle at p from the direction of a to that of b, (−π, π].
double signed_angle_at(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d u = a - p;
  const Vector2d v = b - p;
  return std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v));
}

// Whether the constraints may hold somewhere within `half` (half the block's diagonal) of p;
// with half = 0, whether they hold at p.
bool may_hold(const Vector2d& p, double half, const std::vector<PlacedLandmark>& marks, bool ranges, double scale) {
  thread_local std::vector<double> dist;
  dist.resize(marks.size());
  for (std::size_t i = 0; i < marks.size(); ++i) {
    dist[i] = (marks[i].at - p).norm();
    if (ranges && (dist[i] - half > marks[i].hi || dist[i] + half < marks[i].lo)) return false;
  }
  for (std::size_t i = 0; i < marks.size(); ++i) {
    for (std::size_t j = i + 1; j < marks.size(); ++j) {
      // Within the block the direction to a landmark turns by at most asin(half / distance).
      if (dist[i] <= half || dist[j] <= half) continue;
      const double slack = half > 0 ? std::asin(half / dist[i]) + std::asin(half / dist[j]) : 0;
      const double observed = wrap_angle(marks[j].bearing - marks[i].bearing);
      const double seen = signed_angle_at(p, marks[i].at, marks[j].at);
      if (std::abs(wrap_angle(seen - observed)) > scale * (marks[i].error + marks[j].error) + slack) return false;
    }
  }
  return true;
}

}  // namespace

Circle constant_angle_locus(double s, double theta) {
  return {Vector2d(s / 2, s / 2 / std::tan(theta)), s / 2 / std::sin(theta)};
}

double locus_range(double s, double theta, double phi) {
  return s * std::cos(phi) + s / std::tan(theta) * std::sin(phi);
}

double locus_angle(double r1, double r2, double theta) {
  const double cot_phi = r1 / r2 / std::sin(theta) - 1 / std::tan(theta);
  return std::atan2(1.0, cot_phi);  // φ ∈ (0, π)
}

Localization localize(const Viewframe& view, const FramePositions& positions, const LocalizationOptions& options) {
  Localization out;
  std::vector<PlacedLandmark> marks;
  for (const ViewedLandmark& l : view.landmarks) {
    const auto it = positions.find(l.id);
    if (it == positions.end()) continue;
    marks.push_back({it->second, l.range_lo, l.range_hi, l.bearing, l.error});
  }
  if (marks.size() < 2) return out;
  out.pairs = static_cast<int>(marks.size() * (marks.size() - 1) / 2);
  // The raster's extent: within reach of every landmark's interval (or of the farthest one's
  // upper range when ranges are not used, so the region stays bounded).
  double reach = 0;
  for (const PlacedLandmark& m : marks) reach = std::max(reach, m.hi);
  Vector2d lo = Vector2d::Constant(-std::numeric_limits<double>::infinity());
  Vector2d hi = Vector2d::Constant(std::numeric_limits<double>::infinity());
  for (const PlacedLandmark& m : marks) {
    const double r = options.use_ranges ? m.hi : reach;
    lo = lo.cwiseMax(m.at - Vector2d::Constant(r));
    hi = hi.cwiseMin(m.at + Vector2d::Constant(r));
  }
  if ((hi.array() < lo.array()).any()) return out;
  const double res = options.resolution_mm;
  const auto i0 = static_cast<long>(std::floor(lo.x() / res));
  const auto i1 = static_cast<long>(std::ceil(hi.x() / res));
  const auto j0 = static_cast<long>(std::floor(lo.y() / res));
  const auto j1 = static_cast<long>(std::ceil(hi.y() / res));
  if (static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1) > static_cast<double>(options.max_cells)) {
    return out;
  }
  constexpr long kBlock = 16;
  const double half_block = std::sqrt(2.0) * (kBlock - 1) * res / 2;
  Vector2d sum = Vector2d::Zero();
  out.min = Vector2d::Constant(std::numeric_limits<double>::infinity());
  out.max = -out.min;
  for (long bj = j0; bj <= j1; bj += kBlock) {
    for (long bi = i0; bi <= i1; bi += kBlock) {
      const long ei = std::min(bi + kBlock - 1, i1);
      const long ej = std::min(bj + kBlock - 1, j1);
      const Vector2d centre((bi + ei) * res / 2, (bj + ej) * res / 2);
      if (!may_hold(centre, half_block, marks, options.use_ranges, options.error_scale)) continue;
      for (long j = bj; j <= ej; ++j) {
        for (long i = bi; i <= ei; ++i) {
          const Vector2d p(i * res, j * res);
          if (!may_hold(p, 0, marks, options.use_ranges, options.error_scale)) continue;
          ++out.count;
          sum += p;
          out.min = out.min.cwiseMin(p);
          out.max = out.max.cwiseMax(p);
          if (options.keep_cells) out.cells.push_back(p);
        }
      }
    }
  }
  if (out.count > 0) out.centroid = sum / static_cast<double>(out.count);
  return out;
}

}  // namespace neopipe::nav::qualnav
