#include "nav/nx/learned_map.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace neopipe::nav::nx {

std::size_t LearnedMap::add_place(const PlaceView& view, const Eigen::Vector2d& position) {
  LearnedPlace p;
  p.view = view;
  p.position = position;
  for (const double h : view.slots) p.slots.push_back({h});
  places_.push_back(std::move(p));
  return places_.size() - 1;
}

void LearnedMap::link(std::size_t p, int ps, std::size_t q, int qs, double length, double dtheta_deg) {
  Slot& a = places_.at(p).slots.at(static_cast<std::size_t>(ps));
  a = {a.heading_deg, SlotState::explored, q, qs, length, dtheta_deg};
  Slot& b = places_.at(q).slots.at(static_cast<std::size_t>(qs));
  b = {b.heading_deg, SlotState::explored, p, ps, length, -dtheta_deg};
}

void LearnedMap::mark(std::size_t p, int slot, SlotState state) {
  places_.at(p).slots.at(static_cast<std::size_t>(slot)).state = state;
}

bool LearnedMap::could_be(std::size_t p, const PlaceView& view, double tolerance, double heading_tolerance_deg,
                          std::size_t slots_to_agree) const {
  const PlaceView& known = places_.at(p).view;
  if (std::abs(view.range - known.range) > tolerance * known.range) return false;
  if (slots_to_agree == 0 && view.slots.size() != known.slots.size()) return false;
  std::vector<bool> used(known.slots.size(), false);
  std::size_t agreeing = 0;
  for (const double h : view.slots) {
    for (std::size_t i = 0; i < known.slots.size(); ++i) {
      if (!used[i] && headings_agree(h, known.slots[i], heading_tolerance_deg)) {
        used[i] = true;
        ++agreeing;
        break;
      }
    }
  }
  return slots_to_agree == 0 ? agreeing == known.slots.size() : agreeing >= slots_to_agree;
}

bool LearnedMap::range_fits(std::size_t p, const PlaceView& view, double tolerance) const {
  const double known = places_.at(p).view.range;
  return std::abs(view.range - known) <= tolerance * known;
}

std::vector<std::size_t> LearnedMap::near(const Eigen::Vector2d& position, double radius_mm, const PlaceView& view,
                                          double tolerance) const {
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < places_.size(); ++p) {
    if ((places_[p].position - position).norm() <= radius_mm && range_fits(p, view, tolerance)) out.push_back(p);
  }
  std::stable_sort(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
    return (places_[a].position - position).squaredNorm() < (places_[b].position - position).squaredNorm();
  });
  return out;
}

std::vector<std::size_t> LearnedMap::candidates(const PlaceView& view, double tolerance,
                                                double heading_tolerance_deg) const {
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < places_.size(); ++p) {
    if (could_be(p, view, tolerance, heading_tolerance_deg)) out.push_back(p);
  }
  std::stable_sort(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(places_[a].view.range - view.range) < std::abs(places_[b].view.range - view.range);
  });
  return out;
}

std::vector<double> LearnedMap::distances(std::size_t from, const std::set<std::pair<std::size_t, int>>& avoid) const {
  std::vector<double> dist(places_.size(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist.at(from) = 0;
  queue.emplace(0, from);
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > dist[p]) continue;
    for (const Slot& s : places_[p].slots) {
      if (s.state != SlotState::explored) continue;
      // Distances run backwards from the goal: the leg that would be travelled is (to_place, to_slot).
      if (avoid.contains({s.to_place, s.to_slot})) continue;
      const double nd = d + s.length;
      if (nd < dist[s.to_place]) {
        dist[s.to_place] = nd;
        queue.emplace(nd, s.to_place);
      }
    }
  }
  return dist;
}

std::vector<Leg> LearnedMap::route(std::size_t from, std::size_t to,
                                   const std::set<std::pair<std::size_t, int>>& avoid) const {
  if (from == to || from >= places_.size() || to >= places_.size()) return {};
  // Dijkstra backwards from the goal, then walk forward greedily along the distance field.
  const std::vector<double> to_goal = distances(to, avoid);
  if (!std::isfinite(to_goal[from])) return {};
  std::vector<Leg> legs;
  std::size_t at = from;
  while (at != to && legs.size() <= places_.size()) {
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    const auto& slots = places_[at].slots;
    for (std::size_t s = 0; s < slots.size(); ++s) {
      if (slots[s].state != SlotState::explored || avoid.contains({at, static_cast<int>(s)})) continue;
      const double d = slots[s].length + to_goal[slots[s].to_place];
      if (d < best_d - 1e-9) {
        best = static_cast<int>(s);
        best_d = d;
      }
    }
    if (best < 0) return {};
    legs.push_back({at, best});
    at = slots[static_cast<std::size_t>(best)].to_place;
  }
  return at == to ? legs : std::vector<Leg>{};
}

std::size_t LearnedMap::edges() const {
  std::size_t n = 0;
  for (std::size_t p = 0; p < places_.size(); ++p) {
    for (const Slot& s : places_[p].slots) {
      if (s.state == SlotState::explored && s.to_place >= p) ++n;
    }
  }
  return n;
}

}  // namespace neopipe::nav::nx
