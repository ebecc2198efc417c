#include "nav/qualnav/metric/viewframe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

namespace neopipe::nav::qualnav {

const ViewedLandmark* Viewframe::find(LandmarkId id) const {
  const auto it =
      std::find_if(landmarks.begin(), landmarks.end(), [id](const ViewedLandmark& l) { return l.id == id; });
  return it == landmarks.end() ? nullptr : &*it;
}

Viewframe make_viewframe(std::vector<ViewedLandmark> landmarks, double compass) {
  Viewframe v;
  v.compass = compass;
  std::set<LandmarkId> seen;
  for (ViewedLandmark& l : landmarks) {
    if (!seen.insert(l.id).second) continue;
    l.bearing = std::fmod(std::fmod(l.bearing, 2 * std::numbers::pi) + 2 * std::numbers::pi, 2 * std::numbers::pi);
    v.landmarks.push_back(l);
  }
  // Pan order: clockwise, i.e. by decreasing counter-clockwise bearing; ties by id.
  std::sort(v.landmarks.begin(), v.landmarks.end(), [](const ViewedLandmark& a, const ViewedLandmark& b) {
    return a.bearing != b.bearing ? a.bearing > b.bearing : a.id < b.id;
  });
  return v;
}

double wrap_angle(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

double angle_between(const ViewedLandmark& i, const ViewedLandmark& j) {
  return wrap_angle(j.bearing - i.bearing);
}

std::vector<LandmarkId> shared_landmarks(const Viewframe& a, const Viewframe& b) {
  std::vector<LandmarkId> out;
  for (const ViewedLandmark& l : a.landmarks) {
    if (b.sees(l.id)) out.push_back(l.id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace neopipe::nav::qualnav
