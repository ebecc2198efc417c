#include "nav/tour/cognitive_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace neopipe::nav::tour {
namespace {

constexpr Interval kAnyTurn{-180, 180};

Interval shifted(const Interval& a, const Interval& b) {
  return {a.lo + b.lo, a.hi + b.hi};
}

}  // namespace

CognitiveMap::CognitiveMap(const TourSettings& settings) : settings_(settings) {}

CognitiveMap::ViewFacts& CognitiveMap::facts(ViewId view) {
  return views_[view];
}

PlaceId CognitiveMap::place_of(ViewId view) {
  ViewFacts& f = facts(view);
  if (!f.place) {
    f.place = next_place_++;
    places_.insert(*f.place);
  }
  // The first view with a local heading at a place is its zero.
  if (!f.local_heading) {
    bool any = false;
    for (const auto& [id, g] : views_) any = any || (g.place == f.place && g.local_heading.has_value());
    if (!any) f.local_heading = 0.0;
  }
  return *f.place;
}

void CognitiveMap::merge_places(PlaceId keep, PlaceId gone, double heading_offset) {
  for (auto& [id, f] : views_) {
    if (f.place != gone) continue;
    f.place = keep;
    if (f.local_heading) f.local_heading = *f.local_heading + heading_offset;
  }
  places_.erase(gone);
  std::map<std::pair<PlaceId, PathId>, double> moved;
  for (auto it = position_.begin(); it != position_.end();) {
    if (it->first.first == gone) {
      moved.emplace(std::make_pair(keep, it->first.second), it->second);
      it = position_.erase(it);
    } else {
      ++it;
    }
  }
  for (const auto& [key, value] : moved) position_.emplace(key, value);  // the kept place's own wins
  for (auto* sides : {&right_, &left_}) {
    for (auto& [p, set] : *sides) {
      if (set.erase(gone) > 0) set.insert(keep);
    }
  }
  for (Link& l : links_) {
    if (l.a == gone) l.a = keep;
    if (l.b == gone) l.b = keep;
  }
  std::map<std::pair<PlaceId, PlaceId>, double> straight;
  for (const auto& [key, d] : straight_) {
    straight.emplace(std::make_pair(key.first == gone ? keep : key.first, key.second == gone ? keep : key.second), d);
  }
  straight_ = std::move(straight);
}

void CognitiveMap::merge_paths(PathId keep, PathId gone, bool flip, double offset) {
  const double sign = flip ? -1 : 1;
  for (auto& [id, f] : views_) {
    if (f.path != gone) continue;
    f.path = keep;
    f.direction *= flip ? -1 : 1;
  }
  paths_.erase(gone);
  for (auto it = position_.begin(); it != position_.end();) {
    if (it->first.second == gone) {
      const auto key = std::make_pair(it->first.first, keep);
      const double value = sign * it->second + offset;
      it = position_.erase(it);
      position_.emplace(key, value);
    } else {
      ++it;
    }
  }
  const std::set<PlaceId> right = right_[gone];
  const std::set<PlaceId> left = left_[gone];
  right_.erase(gone);
  left_.erase(gone);
  right_[keep].insert((flip ? left : right).begin(), (flip ? left : right).end());
  left_[keep].insert((flip ? right : left).begin(), (flip ? right : left).end());
}

void CognitiveMap::constrain_heading(ViewId from, Interval change, ViewId to) {
  ViewFacts& a = facts(from);
  ViewFacts& b = facts(to);
  bool any = false;
  for (const auto& [id, f] : views_) any = any || f.heading.has_value();
  if (!any) a.heading = Interval{0, 0};  // the orientation frame starts at the first view
  if (a.heading && !b.heading) {
    b.heading = shifted(*a.heading, change);
  } else if (!a.heading && b.heading) {
    a.heading = Interval{b.heading->lo - change.hi, b.heading->hi - change.lo};
  } else if (a.heading && b.heading) {
    Interval implied = shifted(*a.heading, change);
    // Headings are angles: compare the implied interval with the held one a whole turn apart at most.
    const double turns = std::round(((b.heading->lo + b.heading->hi) - (implied.lo + implied.hi)) / 2 / 360);
    implied = shifted(implied, {360 * turns, 360 * turns});
    const Interval meet{std::max(implied.lo, b.heading->lo), std::min(implied.hi, b.heading->hi)};
    if (meet.lo <= meet.hi) {
      b.heading = meet;
    } else {
      ++heading_conflicts_;
    }
  }
}

void CognitiveMap::assimilate_turn(ViewId view, double alpha, ViewId result) {
  const DistortionHeuristics& h = settings_.heuristics;
  double a = wrap_turn_deg(alpha);
  if (h.right_angles && std::abs(std::abs(a) - 90) <= h.right_angle_tolerance_deg) a = a < 0 ? -90 : 90;
  const PlaceId p = place_of(view);
  ViewFacts& r = facts(result);
  const double lh = *facts(view).local_heading;
  if (r.place && *r.place != p) {
    // Two places are one: bring the other's local headings into this place's frame.
    const double offset = r.local_heading ? lh + a - *r.local_heading : 0;
    merge_places(p, *r.place, offset);
  }
  ViewFacts& res = facts(result);
  res.place = p;
  if (!res.local_heading) res.local_heading = lh + a;
  const TurnKind kind = turn_kind(a, settings_.turn_tolerance_deg);
  const ViewFacts& v = facts(view);
  if ((kind == TurnKind::around || kind == TurnKind::none) && v.path) {
    const int dir = kind == TurnKind::around ? -v.direction : v.direction;
    if (res.path && *res.path != *v.path) {
      merge_paths(*v.path, *res.path, res.direction != dir, 0);
    } else {
      res.path = v.path;
      res.direction = dir;
    }
  }
  constrain_heading(view, {a, a}, result);
}

void CognitiveMap::assimilate_travel(ViewId view, const Travel& travel, ViewId result) {
  const DistortionHeuristics& h = settings_.heuristics;
  const PlaceId p1 = place_of(view);
  const PlaceId p2 = place_of(result);
  ViewFacts& v = facts(view);
  if (!v.path) {
    v.path = next_path_++;
    paths_.insert(*v.path);
    v.direction = 1;  // a path's first direction is +1
    position_.emplace(std::make_pair(p1, *v.path), 0.0);
  }
  const PathId path = *v.path;
  const int dir = v.direction;
  const auto key1 = std::make_pair(p1, path);
  if (!position_.contains(key1)) position_.emplace(key1, 0.0);
  const double pos2 = position_.at(key1) + travel.distance * dir;
  ViewFacts& r = facts(result);
  if (r.path && *r.path != path) {
    // The result's path is this one: merge it, mapping its positions so that p2 lands at pos2.
    const bool flip = r.direction != dir;
    const auto old = position_.find(std::make_pair(p2, *r.path));
    const double at = old != position_.end() ? old->second : 0;
    merge_paths(path, *r.path, flip, pos2 - (flip ? -at : at));
  }
  ViewFacts& res = facts(result);
  res.path = path;
  res.direction = dir;
  position_.emplace(std::make_pair(p2, path), pos2);  // an earlier position stays
  links_.push_back({p1, p2, travel.distance});
  if (h.travel_is_distance) straight_[{std::min(p1, p2), std::max(p1, p2)}] = travel.distance;
  const Interval change = h.straight_travel   ? Interval{0, 0}
                          : travel.dtheta_deg ? Interval{*travel.dtheta_deg, *travel.dtheta_deg}
                                              : kAnyTurn;
  constrain_heading(view, change, result);
}

void CognitiveMap::assimilate_boundaries() {
  if (recent_.size() < 3) return;
  const Remembered& t1 = recent_[0];
  const Remembered& turn = recent_[1];
  const Remembered& t2 = recent_[2];
  if (!std::holds_alternative<Travel>(t1.action) || !std::holds_alternative<Turn>(turn.action) ||
      !std::holds_alternative<Travel>(t2.action) || t1.result != turn.view || turn.result != t2.view) {
    return;
  }
  const TurnKind kind = turn_kind(std::get<Turn>(turn.action).alpha_deg, settings_.turn_tolerance_deg);
  if (kind != TurnKind::right && kind != TurnKind::left) return;  // Around (and 0) add nothing
  const ViewFacts& v2 = views_.at(t1.result);
  const ViewFacts& v3 = views_.at(t2.view);
  const PlaceId p1 = *views_.at(t1.view).place;
  const PlaceId p3 = *views_.at(t2.result).place;
  const PathId path1 = *v2.path;
  const PathId path2 = *v3.path;
  if (path1 == path2) return;
  const bool right = kind == TurnKind::right;
  const bool p3_right = (v2.direction == 1) == right;
  const bool p1_right = (v3.direction == 1) == right;
  (p3_right ? right_ : left_)[path1].insert(p3);
  (p1_right ? right_ : left_)[path2].insert(p1);
}

void CognitiveMap::assimilate(ViewId view, const Action& action, ViewId result) {
  if (const auto* turn = std::get_if<Turn>(&action)) {
    assimilate_turn(view, turn->alpha_deg, result);
  } else {
    assimilate_travel(view, std::get<Travel>(action), result);
  }
  recent_.push_back({view, action, result});
  if (recent_.size() > 3) recent_.pop_front();
  assimilate_boundaries();
}

void CognitiveMap::recognise(ViewId view, double alpha_deg, ViewId other) {
  if (view != other) assimilate_turn(view, alpha_deg, other);
}

std::optional<PlaceId> CognitiveMap::place(ViewId view) const {
  const auto it = views_.find(view);
  return it == views_.end() ? std::nullopt : it->second.place;
}

std::optional<PathId> CognitiveMap::path(ViewId view) const {
  const auto it = views_.find(view);
  return it == views_.end() ? std::nullopt : it->second.path;
}

std::optional<int> CognitiveMap::direction(ViewId view) const {
  const auto it = views_.find(view);
  if (it == views_.end() || !it->second.path) return std::nullopt;
  return it->second.direction;
}

std::vector<PlaceId> CognitiveMap::places() const {
  return {places_.begin(), places_.end()};
}

std::vector<PathId> CognitiveMap::paths() const {
  return {paths_.begin(), paths_.end()};
}

std::vector<PlaceId> CognitiveMap::places_on(PathId path) const {
  std::vector<std::pair<double, PlaceId>> on;
  for (const auto& [key, pos] : position_) {
    if (key.second == path) on.emplace_back(pos, key.first);
  }
  std::sort(on.begin(), on.end());
  std::vector<PlaceId> out;
  out.reserve(on.size());
  for (const auto& [pos, p] : on) out.push_back(p);
  return out;
}

std::optional<int> CognitiveMap::order(PlaceId a, PlaceId b, PathId path) const {
  const auto pa = local_position(a, path);
  const auto pb = local_position(b, path);
  if (!pa || !pb || *pa == *pb) return std::nullopt;
  return *pa < *pb ? 1 : -1;
}

bool CognitiveMap::in_right(PlaceId place, PathId path) const {
  const auto it = right_.find(path);
  return it != right_.end() && it->second.contains(place);
}

bool CognitiveMap::in_left(PlaceId place, PathId path) const {
  const auto it = left_.find(path);
  return it != left_.end() && it->second.contains(place);
}

std::optional<PathId> CognitiveMap::boundary_between(PlaceId a, PlaceId b) const {
  for (const PathId p : paths_) {
    if ((in_right(a, p) && in_left(b, p)) || (in_left(a, p) && in_right(b, p))) return p;
  }
  return std::nullopt;
}

std::vector<PlaceId> CognitiveMap::shortest(PlaceId a, PlaceId b, double* length) const {
  std::map<PlaceId, double> dist;
  std::map<PlaceId, PlaceId> previous;
  using Item = std::pair<double, PlaceId>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[a] = 0;
  queue.emplace(0, a);
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > dist[p]) continue;
    if (p == b) break;
    for (const Link& l : links_) {
      if (l.a != p && l.b != p) continue;
      const PlaceId q = l.a == p ? l.b : l.a;
      const double nd = d + std::abs(l.length);
      const auto it = dist.find(q);
      if (it == dist.end() || nd < it->second) {
        dist[q] = nd;
        previous[q] = p;
        queue.emplace(nd, q);
      }
    }
  }
  if (!dist.contains(b)) return {};
  if (length != nullptr) *length = dist[b];
  std::vector<PlaceId> out{b};
  while (out.back() != a) out.push_back(previous.at(out.back()));
  std::reverse(out.begin(), out.end());
  return out;
}

std::vector<PlaceId> CognitiveMap::route(PlaceId a, PlaceId b) const {
  if (a == b) return {a};
  if (const auto boundary = boundary_between(a, b)) {
    // A -> path -> B: through the place of the boundary path that makes the route shortest.
    std::vector<PlaceId> best;
    double best_length = std::numeric_limits<double>::infinity();
    for (const PlaceId x : places_on(*boundary)) {
      double l1 = 0;
      double l2 = 0;
      std::vector<PlaceId> first = shortest(a, x, &l1);
      const std::vector<PlaceId> second = shortest(x, b, &l2);
      if (first.empty() || second.empty() || l1 + l2 >= best_length) continue;
      first.insert(first.end(), second.begin() + 1, second.end());
      best = std::move(first);
      best_length = l1 + l2;
    }
    if (!best.empty()) return best;
  }
  return shortest(a, b, nullptr);
}

std::optional<double> CognitiveMap::local_heading(ViewId view) const {
  const auto it = views_.find(view);
  return it == views_.end() ? std::nullopt : it->second.local_heading;
}

std::optional<double> CognitiveMap::local_position(PlaceId place, PathId path) const {
  const auto it = position_.find({place, path});
  if (it == position_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> CognitiveMap::path_distance(PlaceId a, PlaceId b, PathId path) const {
  const auto pa = local_position(a, path);
  const auto pb = local_position(b, path);
  if (!pa || !pb) return std::nullopt;
  return std::abs(*pa - *pb);
}

std::optional<Interval> CognitiveMap::heading(ViewId view) const {
  const auto it = views_.find(view);
  return it == views_.end() ? std::nullopt : it->second.heading;
}

std::optional<double> CognitiveMap::distance(PlaceId a, PlaceId b) const {
  const auto it = straight_.find({std::min(a, b), std::max(a, b)});
  if (it == straight_.end()) return std::nullopt;
  return it->second;
}

}  // namespace neopipe::nav::tour
