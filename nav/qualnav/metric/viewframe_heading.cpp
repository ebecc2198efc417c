#include "nav/qualnav/metric/viewframe_heading.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace neopipe::nav::qualnav {

using Eigen::Vector2d;

PairKey make_pair_key(LandmarkId a, LandmarkId b) {
  return a < b ? PairKey{a, b} : PairKey{b, a};
}

std::optional<double> pair_separation(const Viewframe& view, PairKey pair) {
  const ViewedLandmark* i = view.find(pair.first);
  const ViewedLandmark* j = view.find(pair.second);
  if (i == nullptr || j == nullptr) return std::nullopt;
  const double mi = i->range_mid();
  const double mj = j->range_mid();
  return std::sqrt(std::max(0.0, mi * mi + mj * mj - 2 * mi * mj * std::cos(angle_between(*i, *j))));
}

void FrameScales::add(const Viewframe& view) {
  for (std::size_t a = 0; a < view.landmarks.size(); ++a) {
    for (std::size_t b = a + 1; b < view.landmarks.size(); ++b) {
      const PairKey key = make_pair_key(view.landmarks[a].id, view.landmarks[b].id);
      auto& [sum, n] = sums_[key];
      sum += *pair_separation(view, key);
      ++n;
    }
  }
}

std::optional<double> FrameScales::scale(PairKey pair) const {
  const auto it = sums_.find(pair);
  if (it == sums_.end()) return std::nullopt;
  return it->second.first / it->second.second;
}

FramePositions PairFrame::positions() const {
  return {{first, Vector2d::Zero()}, {second, Vector2d(s, 0)}};
}

std::vector<PairFrame> candidate_frames(const Viewframe& a, const Viewframe& b, const FrameScales& scales,
                                        double max_separation) {
  const std::vector<LandmarkId> shared = shared_landmarks(a, b);
  std::vector<std::pair<double, PairFrame>> found;
  for (std::size_t x = 0; x < shared.size(); ++x) {
    for (std::size_t y = x + 1; y < shared.size(); ++y) {
      const ViewedLandmark& ai = *a.find(shared[x]);
      const ViewedLandmark& aj = *a.find(shared[y]);
      const double sep_a = std::abs(angle_between(ai, aj));
      const double sep_b = std::abs(angle_between(*b.find(shared[x]), *b.find(shared[y])));
      if (std::max(sep_a, sep_b) >= max_separation) continue;
      const PairKey key = make_pair_key(shared[x], shared[y]);
      // Neither viewframe in the scales: the two viewframes' own average.
      const double s = scales.scale(key).value_or((*pair_separation(a, key) + *pair_separation(b, key)) / 2);
      if (!(s > 0)) continue;
      const bool ccw = angle_between(ai, aj) > 0;  // aj counter-clockwise of ai
      found.emplace_back(std::min(sep_a, sep_b),
                         PairFrame{ccw ? shared[x] : shared[y], ccw ? shared[y] : shared[x], s});
    }
  }
  // Widest first; ties by ids (the pairs were found in id order).
  std::stable_sort(found.begin(), found.end(), [](const auto& l, const auto& r) { return l.first > r.first; });
  std::vector<PairFrame> out;
  out.reserve(found.size());
  for (const auto& f : found) out.push_back(f.second);
  return out;
}

std::optional<PairFrame> choose_frame(const Viewframe& a, const Viewframe& b, const FrameScales& scales,
                                      double max_separation) {
  std::vector<PairFrame> all = candidate_frames(a, b, scales, max_separation);
  if (all.empty()) return std::nullopt;
  return all.front();
}

Localization localize_in_frame(const Viewframe& view, const PairFrame& frame, const LocalizationOptions& options) {
  const FramePositions positions = frame.positions();
  Localization l = localize(view, positions, options);
  if (!l.empty()) return l;
  LocalizationOptions wider = options;
  wider.error_scale = 4 * options.error_scale;
  l = localize(view, positions, wider);
  if (!l.empty()) return l;
  wider.use_ranges = false;
  return localize(view, positions, wider);
}

double sensor_bearing_of(const Viewframe& view, const PairFrame& frame, const Vector2d& c, const Vector2d& v) {
  const double direction = std::atan2(v.y(), v.x());
  // Average over the two landmarks as unit vectors (the bearings may straddle ±π).
  Vector2d sum = Vector2d::Zero();
  for (const auto& [id, at] : frame.positions()) {
    const ViewedLandmark* l = view.find(id);
    const Vector2d to_l = at - c;
    const double b = direction + l->bearing - std::atan2(to_l.y(), to_l.x());
    sum += Vector2d(std::cos(b), std::sin(b));
  }
  return std::atan2(sum.y(), sum.x());
}

std::optional<ViewframeHeading> viewframe_heading(const Viewframe& from, const Viewframe& to, const FrameScales& scales,
                                                  const LocalizationOptions& options) {
  const std::optional<PairFrame> frame = choose_frame(from, to, scales);
  if (!frame) return std::nullopt;
  const Localization a = localize_in_frame(from, *frame, options);
  const Localization b = localize_in_frame(to, *frame, options);
  if (a.empty() || b.empty()) return std::nullopt;
  ViewframeHeading h;
  h.frame = *frame;
  h.from = a.centroid;
  h.to = b.centroid;
  h.h = b.centroid - a.centroid;
  h.distance = h.h.norm();
  h.sensor_bearing = sensor_bearing_of(from, *frame, a.centroid, h.h);
  return h;
}

}  // namespace neopipe::nav::qualnav
