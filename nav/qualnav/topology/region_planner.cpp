#include "nav/qualnav/topology/region_planner.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <stdexcept>

namespace neopipe::nav::qualnav {
namespace {

double wrap_heading(double angle) {
  constexpr double kTurn = 2 * std::numbers::pi;
  angle = std::fmod(angle, kTurn);
  if (angle <= -std::numbers::pi) angle += kTurn;
  if (angle > std::numbers::pi) angle -= kTurn;
  return angle;
}

std::optional<double> bearing_in(std::span<const Sighting> seen, LandmarkId id) {
  for (const Sighting& s : seen) {
    if (s.id == id) return s.bearing;
  }
  return std::nullopt;
}

// A path of the two-ended search: from its end (start or goal) out through the graph.
struct SearchPath {
  std::vector<std::size_t> nodes;
  bool from_start = true;
  std::optional<double> first_heading;
  bool alive = true;
};

// Where a node lies on the paths of one end: (path, position), the end itself being on every path.
using PathPlaces = std::map<std::size_t, std::pair<std::size_t, std::size_t>>;

constexpr std::size_t kEndItself = static_cast<std::size_t>(-1);

// The plan through a start-side prefix ending at `meet_start` position and a goal-side path met at
// `meet_goal`, the goal side reversed.
std::vector<std::size_t> joined_plan(const std::vector<std::size_t>& start_part, std::size_t goal,
                                     const std::vector<SearchPath>& paths, std::pair<std::size_t, std::size_t> place) {
  std::vector<std::size_t> plan = start_part;
  if (place.first == kEndItself) {
    plan.push_back(goal);
    return plan;
  }
  const std::vector<std::size_t>& q = paths[place.first].nodes;
  for (std::size_t k = place.second + 1; k-- > 0;) plan.push_back(q[k]);
  return plan;
}

std::optional<std::vector<std::size_t>> breadth_first_plan(const RegionGraph& graph, std::size_t start,
                                                           std::size_t goal) {
  const std::size_t n = graph.nodes().size();
  std::vector<std::size_t> parent(n, n);
  std::deque<std::size_t> queue{start};
  parent[start] = start;
  while (!queue.empty()) {
    const std::size_t at = queue.front();
    queue.pop_front();
    if (at == goal) break;
    for (const RegionEdge& e : graph.nodes()[at].edges) {  // sorted by id: ties go to the lower id
      if (parent[e.to] != n) continue;
      parent[e.to] = at;
      queue.push_back(e.to);
    }
  }
  if (parent[goal] == n) return std::nullopt;
  std::vector<std::size_t> plan{goal};
  while (plan.back() != start) plan.push_back(parent[plan.back()]);
  std::reverse(plan.begin(), plan.end());
  return plan;
}

}  // namespace

PairSigns to_pair_signs(std::span<const LandmarkPair> pairs, const SignVector& signs) {
  if (pairs.size() != signs.size()) {
    throw std::invalid_argument("to_pair_signs: " + std::to_string(signs.size()) + " signs for " +
                                std::to_string(pairs.size()) + " pairs");
  }
  PairSigns out;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const LandmarkPair& p = pairs[i];
    const int sign = (signs[i] > 0) - (signs[i] < 0);
    if (p.first < p.second) {
      out[p] = sign;
    } else {
      out[{p.second, p.first}] = -sign;
    }
  }
  return out;
}

RegionObservation observe_regions(std::span<const Sighting> seen, std::optional<double> crossing_heading) {
  RegionObservation o;
  o.bearings.assign(seen.begin(), seen.end());
  o.crossing_heading = crossing_heading;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    for (std::size_t j = i + 1; j < seen.size(); ++j) {
      const bool in_order = seen[i].id < seen[j].id;
      const Sighting& first = in_order ? seen[i] : seen[j];
      const Sighting& second = in_order ? seen[j] : seen[i];
      o.signs[{first.id, second.id}] = orientation_from_bearings(first.bearing, second.bearing);
    }
  }
  return o;
}

std::optional<double> edge_heading(const RegionNode& from, const RegionNode& to,
                                   std::optional<double> crossing_heading) {
  if (crossing_heading) return wrap_heading(*crossing_heading);
  for (const auto& [pair, sign] : from.signs) {
    const auto there = to.signs.find(pair);
    if (there == to.signs.end() || there->second == sign) continue;
    const auto b1 = bearing_in(from.bearings, pair.first);
    const auto b2 = bearing_in(from.bearings, pair.second);
    if (!b1 || !b2) return std::nullopt;
    const double x = std::cos(*b1) + std::cos(*b2);
    const double y = std::sin(*b1) + std::sin(*b2);
    if (std::hypot(x, y) < 1e-9) return std::nullopt;  // 180° apart: on the b part already
    return std::atan2(y, x);
  }
  return std::nullopt;
}

RegionGraph::RegionGraph(std::span<const RegionObservation> observations, std::span<const std::size_t> breaks) {
  for (const RegionObservation& o : observations) {
    const auto [it, fresh] = index_.emplace(o.signs, nodes_.size());
    if (fresh) nodes_.push_back({o.signs, o.bearings, {}});
    node_of_.push_back(it->second);
  }
  for (std::size_t i = 1; i < observations.size(); ++i) {
    if (std::find(breaks.begin(), breaks.end(), i) != breaks.end()) continue;
    const std::size_t from = node_of_[i - 1];
    const std::size_t to = node_of_[i];
    if (from == to) continue;
    const std::optional<double> crossing = observations[i].crossing_heading;
    link(from, to, edge_heading(nodes_[from], nodes_[to], crossing));
    link(to, from,
         crossing ? std::optional<double>(wrap_heading(*crossing + std::numbers::pi))
                  : edge_heading(nodes_[to], nodes_[from], std::nullopt));
  }
}

void RegionGraph::link(std::size_t from, std::size_t to, std::optional<double> heading) {
  std::vector<RegionEdge>& edges = nodes_[from].edges;
  const auto at =
      std::lower_bound(edges.begin(), edges.end(), to, [](const RegionEdge& e, std::size_t id) { return e.to < id; });
  if (at != edges.end() && at->to == to) {
    if (!at->heading) at->heading = heading;  // the first known heading stays
    return;
  }
  edges.insert(at, {to, heading});
}

std::optional<std::size_t> RegionGraph::node_with(const PairSigns& signs) const {
  const auto it = index_.find(signs);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> RegionGraph::heading(std::size_t from, std::size_t to) const {
  for (const RegionEdge& e : nodes_.at(from).edges) {
    if (e.to == to) return e.heading;
  }
  return std::nullopt;
}

bool RegionGraph::adjacent(std::size_t from, std::size_t to) const {
  const auto& edges = nodes_.at(from).edges;
  return std::any_of(edges.begin(), edges.end(), [&](const RegionEdge& e) { return e.to == to; });
}

std::optional<RegionPlan> plan_regions(const RegionGraph& graph, std::size_t start, std::size_t goal) {
  const std::size_t n = graph.nodes().size();
  if (start >= n || goal >= n) {
    throw std::out_of_range("plan_regions: node " + std::to_string(std::max(start, goal)) + " of a graph of " +
                            std::to_string(n));
  }
  const auto finish = [&](std::vector<std::size_t> nodes, bool breadth_first) {
    RegionPlan plan{std::move(nodes), {}, breadth_first};
    for (std::size_t i = 1; i < plan.nodes.size(); ++i)
      plan.headings.push_back(graph.heading(plan.nodes[i - 1], plan.nodes[i]));
    return plan;
  };
  if (start == goal) return finish({start}, false);

  std::vector<SearchPath> paths;
  PathPlaces on_start{{start, {kEndItself, 0}}};
  PathPlaces on_goal{{goal, {kEndItself, 0}}};
  for (const bool from_start : {true, false}) {
    const std::size_t end = from_start ? start : goal;
    PathPlaces& places = from_start ? on_start : on_goal;
    for (const RegionEdge& e : graph.nodes()[end].edges) {
      if (places.contains(e.to)) continue;
      places[e.to] = {paths.size(), 1};
      paths.push_back({{end, e.to}, from_start, e.heading, true});
    }
  }
  // After a step of path p: its tip, or a neighbour of its tip, on a path of the other end.
  const auto try_join = [&](std::size_t p) -> std::optional<std::vector<std::size_t>> {
    const SearchPath& path = paths[p];
    const PathPlaces& other = path.from_start ? on_goal : on_start;
    const std::size_t tip = path.nodes.back();
    std::vector<std::size_t> mine = path.nodes;
    std::optional<std::pair<std::size_t, std::size_t>> place;
    if (const auto it = other.find(tip); it != other.end()) {
      mine.pop_back();  // the other path holds the tip too
      place = it->second;
    } else {
      for (const RegionEdge& e : graph.nodes()[tip].edges) {
        if (const auto at = other.find(e.to); at != other.end()) {
          place = at->second;
          break;
        }
      }
    }
    if (!place) return std::nullopt;
    if (path.from_start) return joined_plan(mine, goal, paths, *place);
    // A goal-side path met a start-side one: the start side's prefix, then this path reversed.
    std::vector<std::size_t> prefix;
    if (place->first == kEndItself) {
      prefix.push_back(start);
    } else {
      const auto& q = paths[place->first].nodes;
      prefix.assign(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(place->second) + 1);
    }
    std::reverse(mine.begin(), mine.end());
    prefix.insert(prefix.end(), mine.begin(), mine.end());
    return prefix;
  };
  for (std::size_t p = 0; p < paths.size(); ++p) {
    if (auto joined = try_join(p)) return finish(std::move(*joined), false);
  }
  for (bool moved = true; moved;) {
    moved = false;
    for (std::size_t p = 0; p < paths.size(); ++p) {
      SearchPath& path = paths[p];
      if (!path.alive) continue;
      PathPlaces& mine = path.from_start ? on_start : on_goal;
      std::optional<std::size_t> best;
      double best_turn = 0;
      for (const RegionEdge& e : graph.nodes()[path.nodes.back()].edges) {
        if (mine.contains(e.to)) continue;
        // Unknown headings rank after every known one (a turn can be at most π).
        const double turn = e.heading && path.first_heading ? std::abs(wrap_heading(*e.heading - *path.first_heading))
                                                            : 2 * std::numbers::pi;
        if (!best || turn < best_turn) {  // edges are sorted by id: ties keep the lower id
          best = e.to;
          best_turn = turn;
        }
      }
      if (!best) {
        path.alive = false;
        continue;
      }
      moved = true;
      mine[*best] = {p, path.nodes.size()};
      path.nodes.push_back(*best);
      if (auto joined = try_join(p)) return finish(std::move(*joined), false);
    }
  }
  auto searched = breadth_first_plan(graph, start, goal);
  if (!searched) return std::nullopt;
  return finish(std::move(*searched), true);
}

RegionShortcut shortcut_to(const RegionNode& target, std::span<const Sighting> view,
                           const std::map<LandmarkId, double>& ranges) {
  RegionShortcut s;
  for (const auto& [pair, sign] : target.signs) {
    const auto b1 = bearing_in(view, pair.first);
    const auto b2 = bearing_in(view, pair.second);
    if (!b1 || !b2) {
      s.reason = "LPB (" + std::to_string(pair.first) + ", " + std::to_string(pair.second) + ") is not in view";
      return s;
    }
    if (orientation_from_bearings(*b1, *b2) != sign) s.separating.push_back(pair);
  }
  if (s.separating.empty()) {
    s.possible = true;
    return s;
  }
  std::vector<Sighting> involved;
  for (const LandmarkPair& p : s.separating) {
    for (const LandmarkId id : {p.first, p.second}) {
      if (!bearing_in(involved, id)) involved.push_back({id, *bearing_in(view, id)});
    }
  }
  const auto order = left_to_right_order(involved);
  if (!order) {
    s.reason = "the separating landmarks leave no gap of 180 degrees: the productions are undefined";
    return s;
  }
  const auto position = [&](LandmarkId id) { return std::find(order->begin(), order->end(), id) - order->begin(); };
  for (const LandmarkPair& p : s.separating) {
    const bool first_left = position(p.first) < position(p.second);
    const LandmarkId left = first_left ? p.first : p.second;
    const LandmarkId right = first_left ? p.second : p.first;
    // §4's crossing rule on the view; l beyond the left landmark is the specifier l[P Q].
    Specifier kind = Specifier::b;
    const auto r_left = ranges.find(left);
    const auto r_right = ranges.find(right);
    if (r_left != ranges.end() && r_right != ranges.end()) {
      const LpbPart part =
          classify_crossing(*bearing_in(view, left), *bearing_in(view, right), r_left->second, r_right->second);
      kind = part == LpbPart::b ? Specifier::b : part == LpbPart::l ? Specifier::l : Specifier::r;
    }
    s.specifiers.push_back({kind, left, right});
  }
  s.production = produce_all(s.specifiers, *order);
  if (!s.production) {
    s.reason = "the production of the separating LPBs is " + std::string(kNoProduction);
    return s;
  }
  s.possible = true;
  return s;
}

std::optional<std::size_t> furthest_shortcut(const RegionGraph& graph, const RegionPlan& plan, std::size_t at,
                                             std::span<const Sighting> view,
                                             const std::map<LandmarkId, double>& ranges) {
  for (std::size_t k = plan.nodes.size(); k-- > at + 1;) {
    if (shortcut_to(graph.nodes()[plan.nodes[k]], view, ranges).possible) return k;
  }
  return std::nullopt;
}

}  // namespace neopipe::nav::qualnav
