#include "nav/qualnav/navigator/region_level.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nav/qualnav/metric/viewframe_heading.hpp"
#include "nav/qualnav/navigator/motion.hpp"
#include "nav/qualnav/navigator/orientation_heading.hpp"
#include "nav/qualnav/navigator/range_guard.hpp"
#include "nav/qualnav/topology/region_planner.hpp"

namespace neopipe::nav::qualnav {
namespace {

using Eigen::Vector2d;

// The region landmarks of a view as compass sightings (counter-clockwise from the world's +x).
std::vector<Sighting> region_sightings(const Viewframe& view, const std::vector<LandmarkId>& ids) {
  std::vector<Sighting> out;
  for (const ViewedLandmark& l : view.landmarks) {
    if (std::binary_search(ids.begin(), ids.end(), l.id)) out.push_back({l.id, wrap_angle(l.bearing + view.compass)});
  }
  return out;
}

std::optional<double> sighting_bearing(const std::vector<Sighting>& seen, LandmarkId id) {
  for (const Sighting& s : seen) {
    if (s.id == id) return s.bearing;
  }
  return std::nullopt;
}

// The node's signs over the pairs the view sees both landmarks of: the LPBs that can be told.
RegionNode told_part(const RegionNode& node, const std::vector<Sighting>& seen) {
  RegionNode out{{}, node.bearings, {}};
  for (const auto& [pair, sign] : node.signs) {
    if (sighting_bearing(seen, pair.first) && sighting_bearing(seen, pair.second)) out.signs[pair] = sign;
  }
  return out;
}

// LPBs of `node` the view sees on the other side; nullopt when it can tell none of them.
std::optional<int> separating_count(const RegionNode& node, const std::vector<Sighting>& seen) {
  int told = 0;
  int differ = 0;
  for (const auto& [pair, sign] : node.signs) {
    const auto b1 = sighting_bearing(seen, pair.first);
    const auto b2 = sighting_bearing(seen, pair.second);
    if (!b1 || !b2) continue;
    ++told;
    differ += static_cast<int>(orientation_from_bearings(*b1, *b2) != sign);
  }
  if (told == 0) return std::nullopt;
  return differ;
}

// Whether the view can tell every LPB whose sign differs between `from` and `to`: entering `to` is
// crossing those, and a crossing hidden from view is no crossing (a marble hiding another otherwise
// let a region whose differences all involve the hidden one pass as entered).
bool tells_crossings(const RegionNode& from, const RegionNode& to, const std::vector<Sighting>& seen) {
  for (const auto& [pair, sign] : to.signs) {
    const auto there = from.signs.find(pair);
    if (there == from.signs.end() || there->second == sign) continue;
    if (!sighting_bearing(seen, pair.first) || !sighting_bearing(seen, pair.second)) return false;
  }
  return true;
}

bool sees_all_of(const RegionNode& node, const std::vector<Sighting>& seen) {
  return std::all_of(node.signs.begin(), node.signs.end(), [&](const auto& entry) {
    return sighting_bearing(seen, entry.first.first) && sighting_bearing(seen, entry.first.second);
  });
}

OrientationKind kind_of_specifier(Specifier s) {
  switch (s) {
    case Specifier::l:
      return OrientationKind::l;
    case Specifier::b:
      return OrientationKind::b;
    case Specifier::r:
      return OrientationKind::r;
    case Specifier::a:
      break;
  }
  return OrientationKind::a;
}

// The region phase of one journey: every move goes through here.
class RegionPhase {
 public:
  RegionPhase(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm, const NavigatorConfig& config,
              const RegionLevelConfig& settings)
      : memory_(memory), goal_(goal), eye_(eye), arm_(arm), config_(config), settings_(settings) {}

  RegionPhaseEnding run();

  NavigationReport& report() { return report_; }
  [[nodiscard]] const Vector2d& position() const { return position_; }
  [[nodiscard]] const std::optional<Vector2d>& last_path_move() const { return last_move_; }

 private:
  RegionPhaseEnding end(RegionPhaseEnding e, std::string reason) {
    report_.reason = std::move(reason);
    report_.regions.ending = region_phase_ending_name(e);
    return e;
  }
  // A look, and its guard (range_guard.hpp, as the viewframe level keeps it).
  Viewframe look() {
    Viewframe v = eye_.look();
    guard_.fuse(v, odometer_);
    return v;
  }
  // One path step towards `bearing` keeping the clearance; false: none keeps it, or the arm refused.
  bool step(double bearing, double length) {
    std::optional<Vector2d> m = safe_move(guard_.guard(), bearing, length, config_.clearance);
    for (int again = 0; !m && again < config_.extra_looks; ++again) {
      look();
      m = safe_move(guard_.guard(), bearing, length, config_.clearance);
    }
    if (!m) return false;
    if (std::abs(wrap_angle(std::atan2(m->y(), m->x()) - bearing)) > 1e-6) ++report_.detours;
    ++report_.steps;
    ++report_.regions.steps;
    if (!arm_.move_relative(m->x(), m->y(), 0)) return false;
    report_.commanded_mm += m->norm();
    report_.path_mm += m->norm();
    report_.regions.path_mm += m->norm();
    odometer_ += m->norm();
    if (report_.path.empty()) report_.path.push_back(position_);
    position_ += *m;
    report_.path.push_back(position_);
    if (last_move_) {
      report_.path_turning +=
          std::abs(std::atan2(last_move_->x() * m->y() - last_move_->y() * m->x(), last_move_->dot(*m)));
    }
    last_move_ = *m;
    return true;
  }
  // The remembered viewframe that stands for `region`: the middle one of those recorded in it.
  std::size_t representative(std::size_t region) const {
    std::vector<std::size_t> in;
    for (std::size_t i = 0; i < graph_->node_of_observation().size(); ++i) {
      if (graph_->node_of_observation()[i] == region) in.push_back(i);
    }
    return in[in.size() / 2];
  }

  const VisualMemory& memory_;
  LandmarkId goal_;
  ViewSource& eye_;
  Arm& arm_;
  const NavigatorConfig& config_;
  const RegionLevelConfig& settings_;
  NavigationReport report_;
  std::optional<RegionGraph> graph_;
  Vector2d position_ = Vector2d::Zero();
  std::optional<Vector2d> last_move_;
  double odometer_ = 0;
  RangeGuard guard_;  // the looks' landmarks, their ranges narrowed by the looks before
};

RegionPhaseEnding RegionPhase::run() {
  report_.regions.used = true;
  const std::vector<LandmarkId> ids = region_landmarks(memory_, goal_, settings_.landmarks, settings_.min_range_mm);
  const std::optional<std::size_t> goal_view = goal_node(memory_, goal_);
  if (!goal_view || ids.size() < 2) return end(RegionPhaseEnding::lost, "the memory holds no region of the goal");
  std::vector<RegionObservation> observations;
  for (const MemoryNode& n : memory_.nodes()) observations.push_back(observe_regions(region_sightings(n.view, ids)));
  graph_.emplace(observations);
  const RegionGraph& graph = *graph_;
  const std::size_t goal_region = graph.node_of_observation()[*goal_view];

  Viewframe now = look();
  std::vector<Sighting> seen = region_sightings(now, ids);
  // The start's region: the remembered one whose visible LPBs disagree least with the view.
  std::optional<std::size_t> start;
  int fewest = std::numeric_limits<int>::max();
  for (std::size_t n = 0; n < graph.nodes().size(); ++n) {
    const std::optional<int> c = separating_count(graph.nodes()[n], seen);
    if (c && *c < fewest) {
      fewest = *c;
      start = n;
    }
  }
  if (!start) return end(RegionPhaseEnding::lost, "no remembered region shares an LPB with the view");
  const std::optional<RegionPlan> plan = plan_regions(graph, *start, goal_region);
  if (!plan) return end(RegionPhaseEnding::lost, "no region plan reaches the goal's region");
  report_.regions.plan_regions = static_cast<int>(plan->nodes.size());

  std::size_t at = 0;
  std::size_t target = 0;
  int best_separating = std::numeric_limits<int>::max();
  int idle = 0;
  int since_crossing = 0;
  while (true) {
    if (report_.steps >= config_.max_steps) {
      return end(RegionPhaseEnding::step_limit, "the step limit ran out at the region level");
    }
    if (const ViewedLandmark* g = now.find(goal_); g != nullptr && g->range_hi <= config_.approach_mm) {
      return end(RegionPhaseEnding::goal_near, "");
    }
    // Entered a later planned region (or overshot into one further on)?
    bool progressed = false;
    for (std::size_t k = plan->nodes.size(); k-- > at + 1;) {
      const RegionNode& there = graph.nodes()[plan->nodes[k]];
      if (separating_count(there, seen).value_or(1) == 0 &&
          tells_crossings(graph.nodes()[plan->nodes[at]], there, seen)) {
        report_.regions.regions_crossed += static_cast<int>(k - at);
        at = k;
        progressed = true;
        break;
      }
    }
    if (at + 1 >= plan->nodes.size()) return end(RegionPhaseEnding::goal_region, "");
    // The paper's shortcut: a later region beyond the one aimed at whose LPBs are all in view and whose
    // separating LPBs have a production. The aim holds until it is reached (or a further one opens):
    // re-aiming every step at whatever the view allows made the heading flicker between targets.
    std::map<LandmarkId, double> ranges;
    for (const ViewedLandmark& l : now.landmarks) ranges[l.id] = l.range;
    if (target <= at) target = at + 1;
    std::optional<RegionShortcut> way;
    for (std::size_t k = plan->nodes.size(); k-- > std::max(target, at + 1) + 1;) {
      const RegionNode& node = graph.nodes()[plan->nodes[k]];
      if (!sees_all_of(node, seen)) continue;
      RegionShortcut s = shortcut_to(node, seen, ranges);
      if (s.possible && s.production) {
        way = std::move(s);
        target = k;
        best_separating = std::numeric_limits<int>::max();
        ++report_.regions.shortcuts;
        break;
      }
    }
    std::size_t aim = target;
    if (!way) way = shortcut_to(told_part(graph.nodes()[plan->nodes[aim]], seen), seen, ranges);
    if (!way->production && aim > at + 1) {
      // The aim's production lapsed: cross into the next region meanwhile.
      RegionShortcut next = shortcut_to(told_part(graph.nodes()[plan->nodes[at + 1]], seen), seen, ranges);
      if (next.production) {
        way = std::move(next);
        aim = at + 1;
      }
    }
    const int separating = static_cast<int>(way->separating.size());
    if (progressed || separating < best_separating) {
      best_separating = separating;
      idle = 0;
    } else if (++idle >= settings_.stall_steps) {
      return end(RegionPhaseEnding::stalled, "the separating LPBs not fewer for " + std::to_string(idle) + " steps");
    }
    // A target that keeps changing resets the count above; no region entered for long is a stall too.
    since_crossing = progressed ? 0 : since_crossing + 1;
    if (since_crossing >= 4 * settings_.stall_steps) {
      return end(RegionPhaseEnding::stalled,
                 "no planned region entered for " + std::to_string(since_crossing) + " steps");
    }

    std::optional<double> bearing;
    double length = config_.step_mm;
    if (way->production) {
      const HeadingSpecifier& h = *way->production;
      bearing = orientation_heading(kind_of_specifier(h.kind), h.left, h.right, now);
      if (bearing) ++report_.regions.production_steps;
    }
    if (!bearing) {
      // "–" or undefined: a viewframe heading to where the memory was in that region.
      const Viewframe& there = memory_.nodes()[representative(plan->nodes[aim])].view;
      const std::optional<ViewframeHeading> h = viewframe_heading(now, there, memory_.scales(), memory_.localization());
      if (!h) return end(RegionPhaseEnding::lost, "no viewframe heading to the next region's viewframe");
      bearing = h->sensor_bearing;
      length = std::clamp(h->distance, config_.step_mm / 2, config_.step_mm);
      ++report_.regions.fallback_steps;
    }
    if (!step(*bearing, length)) return end(RegionPhaseEnding::blocked, "no region-level step keeps the clearance");
    ++report_.heading_steps;
    now = look();
    seen = region_sightings(now, ids);
  }
}

}  // namespace

std::string_view region_phase_ending_name(RegionPhaseEnding e) {
  constexpr std::array<std::string_view, 6> names{"goal_region", "goal_near", "lost",
                                                  "stalled",     "blocked",   "step_limit"};
  return names.at(static_cast<std::size_t>(e));
}

std::vector<LandmarkId> region_landmarks(const VisualMemory& memory, LandmarkId goal, int count, double min_range_mm) {
  std::map<LandmarkId, double> nearest;
  for (const MemoryNode& n : memory.nodes()) {
    for (const ViewedLandmark& l : n.view.landmarks) {
      const auto [it, fresh] = nearest.try_emplace(l.id, l.range);
      if (!fresh) it->second = std::min(it->second, l.range);
    }
  }
  std::vector<std::pair<double, LandmarkId>> by_range;
  for (const auto& [id, range] : nearest) {
    if (id != goal && range >= min_range_mm) by_range.emplace_back(range, id);
  }
  std::sort(by_range.begin(), by_range.end());
  std::vector<LandmarkId> out;
  if (nearest.contains(goal) && count > 0) out.push_back(goal);
  for (const auto& [range, id] : by_range) {
    if (std::ssize(out) >= count) break;
    out.push_back(id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

NavigationReport navigate_regions(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm,
                                  const NavigatorConfig& config, const RegionLevelConfig& regions,
                                  GoalObserver* observer) {
  RegionPhase phase(memory, goal, eye, arm, config, regions);
  const RegionPhaseEnding ending = phase.run();
  NavigationReport head = std::move(phase.report());
  if (ending == RegionPhaseEnding::step_limit) {
    head.ending = NavigationEnding::step_limit;
    return head;
  }
  head.regions.fallbacks =
      static_cast<int>(ending != RegionPhaseEnding::goal_region && ending != RegionPhaseEnding::goal_near);
  NavigatorConfig rest = config;
  rest.max_steps = std::max(0, config.max_steps - head.steps);
  NavigationReport tail = navigate(memory, goal, eye, arm, rest, observer);
  // The journey's whole: the tail's ending and claim, both phases' moves and path.
  NavigationReport whole = std::move(tail);
  whole.steps += head.steps;
  whole.heading_steps += head.heading_steps;
  whole.detours += head.detours;
  whole.commanded_mm += head.commanded_mm;
  whole.path_mm += head.path_mm;
  whole.path_turning += head.path_turning;
  if (phase.last_path_move() && whole.path.size() >= 2) {
    const Vector2d& a = *phase.last_path_move();
    const Vector2d b = whole.path[1] - whole.path[0];
    if (b.norm() > 1e-9) whole.path_turning += std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
  }
  std::vector<Vector2d> path = head.path;
  for (std::size_t i = path.empty() ? 0 : 1; i < whole.path.size(); ++i)
    path.push_back(whole.path[i] + phase.position());
  if (path.empty()) path.assign(whole.path.begin(), whole.path.end());
  whole.path = std::move(path);
  whole.regions = head.regions;
  if (whole.ending != NavigationEnding::arrived && whole.reason.empty()) whole.reason = head.reason;
  return whole;
}

}  // namespace neopipe::nav::qualnav
