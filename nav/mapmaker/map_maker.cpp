#include "nav/mapmaker/map_maker.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace neopipe::nav::mapmaker {
namespace {

constexpr double kSlideSlack = 1.2;

// How many standard deviations of the map-maker's errors a slide's goal may lie from where it is
// expected and still be taken for it: wide enough that the true goal is almost never refused (two
// axes, 6e-5 each), narrow enough to refuse an object a window away.
constexpr double kSlideGoalSds = 4;
// The smallest tolerance: the navigator's own measurement and the adjust's residual, mm.
constexpr double kSlideGoalFloor = 3;

// Where the trajectory's goal lies from its reference in the track's axes, and the tolerances of
// that place: the goal's and the reference's survey errors (sigma per axis each), the direction's
// (the reference's and the direction landmark's errors across a baseline b turn a goal L away by
// sqrt(2) sigma L / b, the arm's heading error by its turn times L), and the arm's over the slide.
SlideGoal slide_goal(const WorldViews& views, const Trajectory& t, const NavigatorErrors& errors) {
  const Eigen::Vector2d ref = views.position(t.from.object);
  const Eigen::Vector2d u = t.heading(views);
  const Eigen::Vector2d n(-u.y(), u.x());
  const Eigen::Vector2d rel = views.position(t.to) - ref;
  const double baseline = (views.position(t.via) - ref).norm();
  const double s2 = errors.sigma * errors.sigma;
  const double arm = errors.translation_per_mm * t.slide;
  const double turn = errors.rotation_per_mm * t.slide * rel.norm();
  // The direction's error turns the goal's place about the reference: across the track for a goal
  // ahead, along it for one far to the side, so both axes get it (counted across only, correct goals
  // 37 mm to the side of their track were refused on a 1.5 mm survey).
  const double turned2 = 2 * s2 * rel.squaredNorm() / (baseline * baseline) + turn * turn;
  const double sd = std::sqrt(2 * s2 + arm * arm + turned2);
  const double tolerance = std::ceil(std::max(kSlideGoalSds * sd, kSlideGoalFloor));
  return {std::round(rel.dot(u)), std::round(rel.dot(n)), tolerance, tolerance};
}

}  // namespace

double Route::ratio() const {
  return distance * std::exp(unreliability);
}

MapMaker::MapMaker(Workspace workspace, const MapMakerOptions& options)
    : workspace_(std::move(workspace)),
      options_(options),
      views_(workspace_, options.window),
      steps_(views_, options.errors, options.extended_descriptions) {}

Route MapMaker::plan(std::uint32_t start, std::uint32_t goal, CostCriterion criterion) const {
  const std::size_t n = workspace_.objects.size();
  for (const auto& [what, id] : {std::pair{"start", start}, std::pair{"goal", goal}}) {
    if (id >= n) {
      throw MapError(fmt::format("{} object {} does not exist (the world has objects 0..{})", what, id,
                                 static_cast<long long>(n) - 1));
    }
  }
  if (start == goal) throw MapError(fmt::format("start and goal are the same object ({})", start));

  // Nodes: 4 per object (its placements) and one goal node. A step that reaches the goal ends
  // there, without adjusting: the navigator only has to identify it.
  const auto goal_node = static_cast<std::uint32_t>(4 * n);
  PlanGraph graph(4 * n + 1);
  std::vector<std::uint32_t> step_of_edge;
  const std::vector<Step>& all = steps_.steps();
  for (std::uint32_t node = 0; node < goal_node; ++node) {
    const auto [begin, end] = steps_.range(node);
    for (std::uint32_t i = begin; i < end; ++i) {
      const Step& s = all[i];
      if (s.landmark == goal) {
        if (s.adjust != kCorners.front()) continue;  // one arrival edge per way of reaching it
        graph.add_edge({node, goal_node, s.arrival_travel, s.unreliability(), s.landmark_distance});
      } else {
        graph.add_edge(
            {node, Placement{s.landmark, s.adjust}.node(), s.travel, s.unreliability(), s.landmark_distance});
      }
      step_of_edge.push_back(i);
    }
  }
  // The compromise D / R rates a route by the travel it costs per success. Identifying a goal in
  // view travels 0 mm but is not free: it costs a look, counted as a window's travel, so a route
  // of D = 0 no longer wins whatever its U.
  graph.set_ratio_offset(views_.window().side);
  std::vector<std::uint32_t> sources;
  sources.reserve(kCorners.size());
  for (const Corner c : kCorners) sources.push_back(Placement{start, c}.node());
  const std::uint32_t targets[] = {goal_node};
  const auto path = plan_path(graph, sources, targets, criterion);
  if (!path) {
    throw UnreachableGoal(
        fmt::format("goal {} cannot be reached from {}: no chain of parkway steps and trajectories "
                    "leads there",
                    goal, start));
  }

  Route route;
  route.start = start;
  route.goal = goal;
  route.criterion = criterion;
  route.distance = path->distance;
  route.unreliability = path->unreliability;
  route.landmark_distance = path->landmark_distance;
  route.start_corner = all[step_of_edge[path->edges.front()]].from.corner;
  route.custom_map.entries.push_back(
      {Description::Any, std::nullopt, {}, route.start_corner, std::nullopt, std::nullopt});
  for (std::size_t k = 0; k < path->edges.size(); ++k) {
    const std::uint32_t e = path->edges[k];
    const bool last = k + 1 == path->edges.size();
    RouteStep rs;
    rs.step = all[step_of_edge[e]];
    rs.distance = graph.edges()[e].distance;
    const Step& s = rs.step;
    std::vector<std::uint32_t> confusable;
    std::optional<Trajectory> trajectory;
    if (s.slide) {
      trajectory = trajectory_from(views_, s.from, s.seek, *s.slide);
      confusable = confusable_on_trajectory(views_, *trajectory, options_.errors);
    } else {
      confusable = confusable_in_view(views_, s.from, s.landmark, s.seek);
    }
    rs.check = check_step(views_, s.landmark, confusable, options_.border_tolerance);
    rs.entry = {s.seek,       s.slide,     rs.check.rules, last ? std::nullopt : std::optional<Corner>(s.adjust),
                std::nullopt, std::nullopt};
    // The goal is always looked around when its QOC is sure, even when some mistake could show the
    // same: arriving at the wrong object is otherwise an unaware failure, and one that shows another
    // QOC sends the navigator back for another candidate.
    // (Measured at every unverifiable step it finds more mistakes than it can undo: on five surveys of
    // two worlds at 1.5 mm the goal rate fell from 91.0% to 88.6%; at the goal alone it rose to 91.8%.)
    if (last && rs.check.kind == Verifiability::unverifiable) {
      rs.entry.rules.push_back(RecoveryRule::verified(rs.check.qoc, true));
    }
    // The verified QOC names its quadrants: a mistake with the same count rarely has the same ones.
    for (RecoveryRule& r : rs.entry.rules) {
      if (!r.corner) r.quadrants = views_.quadrant_pattern(s.landmark, options_.border_tolerance);
    }
    // The navigator stops a slide its landmark has not ended by here: a window beyond the slide,
    // room for what errors move and for the next newcomers when the first proves wrong.
    if (s.slide) {
      rs.entry.slide_limit = std::ceil(kSlideSlack * s.arrival_travel + views_.window().side);
      if (options_.slide_goals) rs.entry.slide_goal = slide_goal(views_, *trajectory, options_.errors);
    }
    route.custom_map.entries.push_back(rs.entry);
    route.forecast *= rs.step.forecast;
    route.steps.push_back(std::move(rs));
  }
  return route;
}

std::string_view step_description(const Step& s) {
  if (s.seek == Description::Far || s.seek == Description::Near) {
    const bool far = s.seek == Description::Far;
    if (!s.slide) return far ? "FAR" : "NEAR";
    if (*s.slide == Direction::positive) return far ? "TRAJP-FAR" : "TRAJP-NEAR";
    return far ? "TRAJN-FAR" : "TRAJN-NEAR";
  }
  if (s.slide) return *s.slide == Direction::positive ? "TRAJP" : "TRAJN";
  return s.seek == Description::Obvious ? "OBVIOUS" : "ISOL";
}

namespace {

// A step's share of what the route's criterion minimises (for ratio, its own D / R).
double step_cost(CostCriterion criterion, const RouteStep& rs) {
  switch (criterion) {
    case CostCriterion::distance:
      return rs.distance;
    case CostCriterion::reliability:
      return rs.step.unreliability();
    case CostCriterion::ratio:
      return rs.distance * std::exp(rs.step.unreliability());
    case CostCriterion::landmark:
      return rs.step.landmark_distance;
  }
  return rs.distance;
}

}  // namespace

std::string route_table(const Route& route) {
  std::string out = fmt::format("{:>6} {:>6} {:<10} {:>9} {:>8} {:>9}  {}\n", "FROM", "TO", "DESC", "DISTANCE",
                                "UNPROB", "COST", "VERIFICATION");
  for (const RouteStep& rs : route.steps) {
    const Step& s = rs.step;
    const std::string_view desc = step_description(s);
    out += fmt::format("{:>6} {:>6} {:<10} {:>9.3f} {:>8.3f} {:>9.3f}  {}\n", s.from.object, s.landmark, desc,
                       rs.distance, s.unreliability(), step_cost(route.criterion, rs), verification_line(rs.check));
  }
  out += fmt::format("total: D {:.3f} mm, U {:.3f}, D/R {:.3f}, landmark-based distance {:.3f} mm, {} steps\n",
                     route.distance, route.unreliability, route.ratio(), route.landmark_distance, route.steps.size());
  return out;
}

}  // namespace neopipe::nav::mapmaker
