#include "nav/qualnav/topology/lpb.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace neopipe::nav::qualnav {

char part_letter(LpbPart part) {
  switch (part) {
    case LpbPart::l:
      return 'l';
    case LpbPart::b:
      return 'b';
    case LpbPart::r:
      return 'r';
  }
  return '?';
}

double pan_angle(double bearing1, double bearing2) {
  constexpr double kTurn = 2 * std::numbers::pi;
  double theta = std::fmod(bearing1 - bearing2, kTurn);
  if (theta < 0) theta += kTurn;
  // fmod of a tiny negative difference plus 2π rounds to exactly 2π: that is the angle 0.
  return theta >= kTurn ? 0.0 : theta;
}

int orientation_from_bearings(double bearing1, double bearing2, double tolerance) {
  const double off = pan_angle(bearing1, bearing2) - std::numbers::pi;
  if (std::abs(off) <= tolerance) return 0;
  return off < 0 ? +1 : -1;
}

int orientation_from_positions(const Eigen::Vector2d& l1, const Eigen::Vector2d& l2, const Eigen::Vector2d& observer,
                               double tolerance) {
  const Eigen::Vector2d a = l1 - observer;
  const Eigen::Vector2d b = l2 - observer;
  const double cross = a.x() * b.y() - a.y() * b.x();
  if (std::abs(cross) <= tolerance * a.norm() * b.norm()) return 0;
  return cross < 0 ? +1 : -1;
}

LpbPart part_of_line(const Eigen::Vector2d& l1, const Eigen::Vector2d& l2, const Eigen::Vector2d& on_line) {
  const Eigen::Vector2d d = l2 - l1;
  const double length2 = d.squaredNorm();
  if (!(length2 > 0)) throw std::invalid_argument("part_of_line: L1 and L2 coincide, so they span no line");
  const double t = (on_line - l1).dot(d) / length2;
  if (t < 0) return LpbPart::l;
  if (t > 1) return LpbPart::r;
  return LpbPart::b;
}

LpbPart classify_crossing(double bearing1_before, double bearing2_before, double range1_before, double range2_before) {
  const double theta = pan_angle(bearing1_before, bearing2_before);
  const double separation = std::min(theta, 2 * std::numbers::pi - theta);
  if (separation > std::numbers::pi / 2) return LpbPart::b;
  return range1_before < range2_before ? LpbPart::l : LpbPart::r;
}

SignVector sign_vector(std::span<const Eigen::Vector2d> landmarks, std::span<const LandmarkPair> pairs,
                       const Eigen::Vector2d& observer, double tolerance) {
  SignVector signs;
  signs.reserve(pairs.size());
  for (const LandmarkPair& p : pairs) {
    if (p.first >= landmarks.size() || p.second >= landmarks.size()) {
      throw std::out_of_range("sign_vector: pair (" + std::to_string(p.first) + ", " + std::to_string(p.second) +
                              ") names a landmark beyond the " + std::to_string(landmarks.size()) + " given");
    }
    signs.push_back(static_cast<std::int8_t>(
        orientation_from_positions(landmarks[p.first], landmarks[p.second], observer, tolerance)));
  }
  return signs;
}

SignVector sign_vector_from_bearings(std::span<const Sighting> seen, std::span<const LandmarkPair> pairs,
                                     double tolerance) {
  const auto bearing_of = [&](LandmarkId id) {
    for (const Sighting& s : seen) {
      if (s.id == id) return s.bearing;
    }
    throw std::invalid_argument("sign_vector_from_bearings: landmark " + std::to_string(id) + " is not in view");
  };
  SignVector signs;
  signs.reserve(pairs.size());
  for (const LandmarkPair& p : pairs) {
    signs.push_back(
        static_cast<std::int8_t>(orientation_from_bearings(bearing_of(p.first), bearing_of(p.second), tolerance)));
  }
  return signs;
}

std::vector<LandmarkPair> all_pairs(std::span<const LandmarkId> ids) {
  std::vector<LandmarkPair> pairs;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) pairs.push_back({ids[i], ids[j]});
  }
  return pairs;
}

}  // namespace neopipe::nav::qualnav
