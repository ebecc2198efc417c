#include "nav/qualnav/navigator/navigator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>

#include "nav/qualnav/metric/localization.hpp"
#include "nav/qualnav/metric/viewframe_heading.hpp"
#include "nav/qualnav/navigator/range_guard.hpp"

namespace neopipe::nav::qualnav {
namespace {

using Eigen::Vector2d;
using FrameKey = std::pair<LandmarkId, LandmarkId>;  // (L1, L2) of a PairFrame

Vector2d unit_of(double bearing) {
  return {std::cos(bearing), std::sin(bearing)};
}

// A heading from the view just taken to a remembered viewframe.
struct StepHeading {
  double distance = 0;
  double bearing = 0;  // sensor frame
};

// Localizations of the remembered viewframes, by node and frame, kept for the whole journey, and
// the heuristic's headings between remembered viewframes.
class MemoryHeadings {
 public:
  explicit MemoryHeadings(const VisualMemory& memory) : memory_(memory) {}

  // The heading from `now` (localized per frame in `now_cache`) to node `n`, averaged over up to
  // `frames` frames as moves in the sensor frame.
  std::optional<StepHeading> from_view(const Viewframe& now, std::map<FrameKey, Localization>& now_cache, std::size_t n,
                                       int frames) {
    const Viewframe& there = memory_.nodes()[n].view;
    Vector2d sum = Vector2d::Zero();
    int used = 0;
    for (const PairFrame& frame : candidate_frames(now, there, memory_.scales())) {
      if (used >= frames) break;
      const FrameKey key{frame.first, frame.second};
      auto here = now_cache.find(key);
      if (here == now_cache.end()) {
        here = now_cache.emplace(key, localize_in_frame(now, frame, memory_.localization())).first;
      }
      const Localization& a = here->second;
      const Localization& b = node_localization(n, frame);
      if (a.empty() || b.empty()) continue;
      const Vector2d h = b.centroid - a.centroid;
      sum += h.norm() * unit_of(sensor_bearing_of(now, frame, a.centroid, h));
      ++used;
    }
    if (used == 0) return std::nullopt;
    const Vector2d mean = sum / used;
    return StepHeading{mean.norm(), std::atan2(mean.y(), mean.x())};
  }

  // The spec's heuristic: heading length from node n to the goal node when they share a pair.
  double to_goal(std::size_t n, std::size_t goal) {
    if (n == goal) return 0;
    const auto it = heuristic_.find(n);
    if (it != heuristic_.end()) return it->second;
    const auto h = viewframe_heading(memory_.nodes()[n].view, memory_.nodes()[goal].view, memory_.scales(),
                                     memory_.localization());
    return heuristic_[n] = h ? h->distance : 0.0;
  }

 private:
  const Localization& node_localization(std::size_t n, const PairFrame& frame) {
    const auto key = std::make_tuple(n, frame.first, frame.second);
    auto it = nodes_.find(key);
    if (it == nodes_.end()) {
      it = nodes_.emplace(key, localize_in_frame(memory_.nodes()[n].view, frame, memory_.localization())).first;
    }
    return it->second;
  }

  const VisualMemory& memory_;
  std::map<std::tuple<std::size_t, LandmarkId, LandmarkId>, Localization> nodes_;
  std::map<std::size_t, double> heuristic_;
};

// One journey's state: the report, and every move goes through here.
class Journey {
 public:
  Journey(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm, const NavigatorConfig& config,
          GoalObserver* observer)
      : memory_(memory), goal_(goal), eye_(eye), arm_(arm), config_(config), observer_(observer), headings_(memory) {}

  NavigationReport run();

 private:
  bool out_of_steps() const { return report_.steps >= config_.max_steps; }
  NavigationReport end(NavigationEnding e, std::string reason) {
    report_.ending = e;
    report_.reason = std::move(reason);
    return report_;
  }
  // Commands a move; false when the arm refuses it. A path move counts towards the turning.
  bool move(const Vector2d& m, bool path = false) {
    ++report_.steps;
    if (!arm_.move_relative(m.x(), m.y(), 0)) return false;
    report_.commanded_mm += m.norm();
    position_ += m;
    odometer_ += m.norm();
    if (path) {
      report_.path_mm += m.norm();
      if (report_.path.empty()) report_.path.push_back(position_ - m);
      report_.path.push_back(position_);
    }
    if (path && m.norm() > 1e-9) {
      if (last_path_move_) {
        const Vector2d& p = *last_path_move_;
        report_.path_turning += std::abs(std::atan2(p.x() * m.y() - p.y() * m.x(), p.dot(m)));
      }
      last_path_move_ = m;
    }
    return true;
  }
  // A clearance-keeping move towards `bearing`; nullopt: none is safe.
  // A look, and its guard: the same landmarks with range bounds fused over the looks so far.
  Viewframe look() {
    Viewframe v = eye_.look();
    guard_.fuse(v, odometer_);
    return v;
  }
  // A clearance-keeping move towards `bearing` by the latest look's guard; nullopt: none is safe.
  std::optional<Vector2d> safe(const Viewframe& /*now*/, double bearing, double length,
                               std::optional<LandmarkId> ignore) {
    std::optional<Vector2d> m = safe_move(guard_.guard(), bearing, length, config_.clearance, ignore);
    // Blocked by range bounds too loose to tell: look again from here; each look's range error is
    // drawn afresh, so the fused bounds close in on the truth.
    for (int again = 0; !m && again < config_.extra_looks; ++again) {
      look();
      m = safe_move(guard_.guard(), bearing, length, config_.clearance, ignore);
    }
    if (m && std::abs(wrap_angle(std::atan2(m->y(), m->x()) - bearing)) > 1e-6) ++report_.detours;
    return m;
  }
  std::optional<NavigationReport> climb(std::size_t goal_node);
  NavigationReport approach();

  const VisualMemory& memory_;
  LandmarkId goal_;
  ViewSource& eye_;
  Arm& arm_;
  const NavigatorConfig& config_;
  GoalObserver* observer_;
  MemoryHeadings headings_;
  NavigationReport report_;
  std::optional<Vector2d> last_path_move_;
  Vector2d position_ = Vector2d::Zero();  // dead reckoning of the commanded moves
  double odometer_ = 0;                   // mm commanded so far
  RangeGuard guard_;                      // the looks' landmarks, their ranges narrowed by the looks before
  std::optional<Vector2d> smoothed_;      // the running mean of the heading steps' directions
};

NavigationReport Journey::run() {
  const std::optional<std::size_t> target_node = goal_node(memory_, goal_);
  if (!target_node) return end(NavigationEnding::no_memory, "no remembered viewframe sees the goal");
  const std::size_t gn = *target_node;
  const std::size_t n_nodes = memory_.nodes().size();
  std::vector<std::size_t> previous;
  while (!out_of_steps()) {
    const Viewframe now = look();
    if (const ViewedLandmark* g = now.find(goal_); g != nullptr && g->range_hi <= config_.approach_mm) {
      return approach();
    }
    // The view as node n_nodes, linked to the remembered viewframes near it.
    std::map<FrameKey, Localization> now_cache;
    std::vector<std::optional<StepHeading>> to(n_nodes);
    std::vector<std::vector<MemoryLink>> graph = memory_.links();
    graph.emplace_back();
    std::optional<std::size_t> nearest;
    for (std::size_t n = 0; n < n_nodes; ++n) {
      if (shared_landmarks(now, memory_.nodes()[n].view).size() < 2) continue;
      to[n] = headings_.from_view(config_.fused_ranges ? guard_.guard() : now, now_cache, n, config_.frames);
      if (!to[n]) continue;
      if (!nearest || to[n]->distance < to[*nearest]->distance) nearest = n;
      // A node the robot already stands on is no step: links to it would stall the plan there.
      const bool underfoot = to[n]->distance < config_.step_mm / 2 && n != gn;
      if (to[n]->distance <= config_.link_mm && !underfoot) graph.back().push_back({n, to[n]->distance});
    }
    if (!nearest) return end(NavigationEnding::lost, "no remembered viewframe shares a localizable pair with the view");
    if (graph.back().empty()) graph.back().push_back({*nearest, to[*nearest]->distance});  // rule (2): chain back
    const std::vector<std::size_t> plan =
        astar(graph, n_nodes, gn, [&](std::size_t n) { return n == n_nodes ? 0.0 : headings_.to_goal(n, gn); });
    ++report_.replans;
    if (plan.size() < 2) return end(NavigationEnding::lost, "the memory's links do not reach the goal's viewframe");
    const std::size_t target = plan[1];
    if (report_.first_plan.empty()) report_.first_plan.assign(plan.begin() + 1, plan.end());
    if (previous.size() >= 2) {
      const auto at = std::find(previous.begin(), previous.end(), target);
      if (at != previous.end() && at - previous.begin() > 1) ++report_.shortcuts;
    }
    previous = plan;
    const StepHeading& h = *to[target];
    if (target == gn && h.distance < config_.handover_mm) {
      if (config_.hill_climb) {
        if (auto ended = climb(gn)) return *ended;
      }
      return approach();
    }
    double bearing = h.bearing;
    if (config_.steer_by_angles) {
      if (const std::optional<ClimbState> c = climb_state(now, memory_.nodes()[target].view); c && c->pairs >= 2) {
        const Vector2d down = climb_step(*c, config_.climb);
        if (!down.isZero()) bearing = std::atan2(down.y(), down.x());
      }
    }
    // Steady the steering: each heading is one noisy estimate, so the step follows their running
    // mean (the tool never turns, so directions in its frame add up).
    if (smoothed_ && config_.smoothing > 0) {
      const Vector2d blended = config_.smoothing * *smoothed_ + (1 - config_.smoothing) * unit_of(bearing);
      if (blended.norm() > 1e-6) bearing = std::atan2(blended.y(), blended.x());
    }
    smoothed_ = unit_of(bearing);
    const std::optional<Vector2d> m = safe(now, bearing, std::min(config_.step_mm, h.distance), std::nullopt);
    if (!m) return end(NavigationEnding::blocked, "no step towards the next viewframe keeps the clearance");
    if (!move(*m, true)) return end(NavigationEnding::blocked, "the arm refused a step");
    ++report_.heading_steps;
  }
  return end(NavigationEnding::step_limit, "the step limit ran out before the goal");
}

// Descends the goal viewframe's relative angles; nullopt hands over to the a heading (done or
// stalled), a report ends the journey.
std::optional<NavigationReport> Journey::climb(std::size_t gn) {
  const Viewframe& goal_view = memory_.nodes()[gn].view;
  double best = std::numeric_limits<double>::infinity();
  int stalled = 0;
  while (!out_of_steps()) {
    const Viewframe now = look();
    const std::optional<ClimbState> s = climb_state(now, goal_view);
    if (!s || s->worst_error < config_.climb.done_error) return std::nullopt;
    if (s->cost < best) {
      best = s->cost;
      stalled = 0;
    } else if (++stalled >= config_.climb.stall_steps) {
      return std::nullopt;
    }
    const Vector2d step = climb_step(*s, config_.climb);
    if (step.isZero()) return std::nullopt;
    const std::optional<Vector2d> m = safe(now, std::atan2(step.y(), step.x()), step.norm(), std::nullopt);
    if (!m) return std::nullopt;
    if (!move(*m, true)) return end(NavigationEnding::blocked, "the arm refused a hill-climb step");
    ++report_.climb_steps;
  }
  return end(NavigationEnding::step_limit, "the step limit ran out while hill-climbing");
}

NavigationReport Journey::approach() {
  const double near = config_.stop_mm + 5;
  const auto look_goal = [&]() -> std::optional<ViewedLandmark> {
    const Viewframe v = look();
    const ViewedLandmark* g = v.find(goal_);
    if (g == nullptr) return std::nullopt;
    return *g;
  };
  // Towards the goal without overshooting: its true range is at least range_lo.
  Viewframe now = look();
  std::optional<double> last_goal_bearing;
  int hidden = 0;
  while (true) {
    if (out_of_steps()) return end(NavigationEnding::step_limit, "the step limit ran out on the goal's a heading");
    const ViewedLandmark* g = now.find(goal_);
    if (g == nullptr) {
      // Hidden behind a nearer marble: step aside of where it was last seen, a few times.
      if (!last_goal_bearing || ++hidden > 4)
        return end(NavigationEnding::goal_lost, "the goal left the view on its a heading");
      const double side = hidden % 2 == 1 ? 1.0 : -1.0;
      const std::optional<Vector2d> m =
          safe(now, *last_goal_bearing + side * std::numbers::pi / 2, config_.parallax_mm * hidden, goal_);
      if (!m || !move(*m)) return end(NavigationEnding::goal_lost, "the goal left the view on its a heading");
      ++report_.approach_steps;
      now = look();
      continue;
    }
    last_goal_bearing = g->bearing;
    if (g->range_lo <= near) break;
    const double length = std::min(config_.step_mm, g->range_lo - (config_.stop_mm + 1));
    const std::optional<Vector2d> m = safe(now, g->bearing, length, goal_);
    if (!m) return end(NavigationEnding::blocked, "no step towards the goal keeps the clearance");
    if (!move(*m, true)) return end(NavigationEnding::blocked, "the arm refused a step towards the goal");
    ++report_.approach_steps;
    now = look();
  }
  // The range by parallax: a sideways move, a second bearing.
  const auto parallax = [&](const Viewframe& v) -> std::optional<std::pair<double, double>> {
    const ViewedLandmark* g = v.find(goal_);
    if (g == nullptr) return std::nullopt;
    // Sideways first; any move across the bearing gives a parallax, so then obliquely and shorter.
    constexpr std::array<double, 6> kTurns{90, -90, 120, -120, 60, -60};
    for (int k = 0; k < 12 * (config_.extra_looks + 1); ++k) {
      if (k > 0 && k % 12 == 0) look();  // none clear: tighten the bounds from here, try again
      const double length = k % 12 < 6 ? config_.parallax_mm : config_.parallax_mm / 2;
      const Vector2d m = length * unit_of(g->bearing + kTurns[k % 6] * std::numbers::pi / 180);
      const bool clear =
          std::all_of(guard_.guard().landmarks.begin(), guard_.guard().landmarks.end(), [&](const ViewedLandmark& l) {
            const double gap = track_gap(l, m);
            return l.id == goal_ || gap >= config_.clearance.required() || gap >= current_gap(l);
          });
      if (!clear) continue;
      if (!move(m)) return std::nullopt;
      ++report_.approach_steps;
      const std::optional<ViewedLandmark> after = look_goal();
      if (!after) return std::nullopt;
      const std::optional<double> range = parallax_range(g->bearing, m, after->bearing);
      return std::make_pair(range.value_or(after->range), after->bearing);
    }
    return std::nullopt;
  };
  std::optional<std::pair<double, double>> fix = parallax(now);
  if (!fix) return end(NavigationEnding::blocked, "no parallax move keeps the clearance beside the goal");
  // To the stop, then fix the range again where it counts.
  const Vector2d to_stop = (fix->first - config_.stop_mm) * unit_of(fix->second);
  if (!move(to_stop)) return end(NavigationEnding::blocked, "the arm refused the move to the stop");
  ++report_.approach_steps;
  fix = parallax(look());
  if (!fix) return end(NavigationEnding::blocked, "no parallax move keeps the clearance at the stop");
  const Vector2d back = (fix->first - config_.stop_mm) * unit_of(fix->second);
  if (!move(back)) return end(NavigationEnding::blocked, "the arm refused the move to the stop");
  ++report_.approach_steps;
  const std::optional<ViewedLandmark> last = look_goal();
  if (!last) return end(NavigationEnding::goal_lost, "the goal left the view at the stop");
  report_.goal_range_mm = config_.stop_mm;
  report_.claimed_offset = config_.stop_mm * unit_of(last->bearing);
  if (observer_ != nullptr) observer_->goal_held(report_.claimed_offset);
  return end(NavigationEnding::arrived, "");
}

}  // namespace

std::string_view navigation_ending_name(NavigationEnding e) {
  constexpr std::array<std::string_view, kNavigationEndings> names{"arrived",   "no_memory",  "lost",
                                                                   "goal_lost", "step_limit", "blocked"};
  return names.at(static_cast<std::size_t>(e));
}

std::optional<std::size_t> goal_node(const VisualMemory& memory, LandmarkId goal) {
  std::optional<std::size_t> best;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < memory.nodes().size(); ++n) {
    const ViewedLandmark* g = memory.nodes()[n].view.find(goal);
    if (g != nullptr && g->range < nearest) {
      nearest = g->range;
      best = n;
    }
  }
  return best;
}

NavigationReport navigate(const VisualMemory& memory, LandmarkId goal, ViewSource& eye, Arm& arm,
                          const NavigatorConfig& config, GoalObserver* observer) {
  return Journey(memory, goal, eye, arm, config, observer).run();
}

}  // namespace neopipe::nav::qualnav
