#include "nav/nx/controls.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <ranges>

namespace neopipe::nav::nx {
namespace {

Eigen::Vector2d perpendicular(const Eigen::Vector2d& v) {
  return {-v.y(), v.x()};
}

// The Newton step toward r1 = r2 = r3 from three measured neighbours, at most `max_step` long.
Eigen::Vector2d newton_step(const std::vector<Neighbour>& n, double max_step) {
  Eigen::Matrix2d a;
  a.row(0) = (n[0].away - n[1].away).transpose();
  a.row(1) = (n[0].away - n[2].away).transpose();
  const Eigen::Vector2d b(n[1].range - n[0].range, n[2].range - n[0].range);
  Eigen::Vector2d d;
  if (std::abs(a.determinant()) > 1e-3) {
    d = a.partialPivLu().solve(b);
  } else {
    // Nearly collinear gradients: step away from the nearest marble by half the spread.
    d = n[0].away * 0.5 * (n[2].range - n[0].range);
  }
  if (d.norm() > max_step) d *= max_step / d.norm();
  return d;
}

double spread_of(const std::vector<Neighbour>& n) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0;
  for (std::size_t i = 0; i < 3 && i < n.size(); ++i) {
    lo = std::min(lo, n[i].range);
    hi = std::max(hi, n[i].range);
  }
  return hi - lo;
}

// The third smallest non-zero range of a scan (infinity with fewer than three).
double third_range(const Scan& scan) {
  std::vector<double> v;
  for (const double r : scan) {
    if (r > 0) v.push_back(r);
  }
  if (v.size() < 3) return std::numeric_limits<double>::infinity();
  std::nth_element(v.begin(), v.begin() + 2, v.end());
  return v[2];
}

}  // namespace

bool headings_agree(double a_deg, double b_deg, double tolerance_deg) {
  return std::abs(wrap180(a_deg - b_deg)) <= tolerance_deg;
}

std::pair<int, double> nearest_slot(const PlaceView& view, double heading_deg) {
  int best = -1;
  double best_off = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < view.slots.size(); ++i) {
    const double off = std::abs(wrap180(view.slots[i] - heading_deg));
    if (off < best_off) {
      best = static_cast<int>(i);
      best_off = off;
    }
  }
  return {best, best_off};
}

Climb climb_to_place(Robot& robot) {
  const NxConfig& c = robot.config();
  Climb climb;
  for (climb.steps = 0; climb.steps < c.max_climb_steps; ++climb.steps) {
    const std::vector<Neighbour> n = robot.neighbours(3);
    if (n.size() < 3) {
      climb.ending = ClimbEnding::too_few_marbles;
      return climb;
    }
    climb.spread = spread_of(n);
    if (n[0].range < c.clearance_mm) {
      climb.ending = ClimbEnding::too_close;
      return climb;
    }
    Eigen::Vector2d d = newton_step(n, c.max_climb_step_mm);
    // Never step closer to a marble than the clearance (as the linearised ranges predict).
    for (const Neighbour& m : n) {
      const double predicted = m.range + m.away.dot(d);
      if (predicted < c.clearance_mm && m.away.dot(d) < 0) {
        d *= std::max(0.0, (m.range - c.clearance_mm) / -m.away.dot(d));
      }
    }
    const double noise_floor = 2 * c.range_error * n[0].range / std::sqrt(std::max(1, c.reads));
    if (climb.spread <= c.place_tolerance_mm + noise_floor && d.norm() <= c.place_tolerance_mm + noise_floor / 2) {
      climb.ending = ClimbEnding::place;
      return climb;
    }
    if (!robot.move(d)) {
      climb.ending = ClimbEnding::no_convergence;
      return climb;
    }
    climb.moved += d;
  }
  // Out of steps: under noise, or where a marble sits on a sector's edge and its gradient is read
  // from its neighbour's sector, the last steps jitter about the vertex; accept a small spread.
  const double loose = 4 * c.place_tolerance_mm + 0.5 + 3 * c.range_error * 30;
  climb.ending = climb.spread <= loose ? ClimbEnding::place : ClimbEnding::no_convergence;
  return climb;
}

std::optional<PlaceView> describe_place(Robot& robot, int reads) {
  robot.read_heading();
  const std::vector<Neighbour> n = robot.neighbours(3, reads);
  if (n.size() < 3) return std::nullopt;
  PlaceView v;
  for (int i = 0; i < 3; ++i) {
    v.range += n[static_cast<std::size_t>(i)].range / 3;
    v.marble_bearings.push_back(robot.compass_heading(-n[static_cast<std::size_t>(i)].away));
    v.marble_ranges.push_back(n[static_cast<std::size_t>(i)].range);
  }
  // The edge between marbles i and j runs perpendicular to u_i − u_j, away from the third, k:
  // along it r_k grows faster than r_i, (u_i − u_k) · t > 0.
  for (const auto& [i, j, k] : {std::array{0, 1, 2}, std::array{0, 2, 1}, std::array{1, 2, 0}}) {
    const Eigen::Vector2d ui = -n[static_cast<std::size_t>(i)].away;
    const Eigen::Vector2d uj = -n[static_cast<std::size_t>(j)].away;
    const Eigen::Vector2d uk = -n[static_cast<std::size_t>(k)].away;
    Eigen::Vector2d t = perpendicular(ui - uj);
    if (t.norm() < 1e-6) continue;
    t.normalize();
    if ((ui - uk).dot(t) < 0) t = -t;
    v.slots.push_back(robot.compass_heading(t));
  }
  std::sort(v.slots.begin(), v.slots.end());
  return v;
}

EdgeRun follow_edge(Robot& robot, double heading_deg) {
  const NxConfig& c = robot.config();
  EdgeRun run;
  Eigen::Vector2d t = robot.tool_direction(heading_deg);
  const auto step = [&](const Eigen::Vector2d& d) {
    if (!robot.move(d)) return false;
    run.moves.push_back(d);
    run.displacement += d;
    return true;
  };
  // A short first step, so that an edge shorter than step_mm still ends at its own place.
  const double first = std::min(c.step_mm, 2.0);
  if (!step(first * t)) {
    run.ending = EdgeEnding::blocked;
    return run;
  }
  run.length = first;
  double last_gap = 0;
  bool retried = false;
  while (true) {
    const std::vector<Neighbour> n = robot.neighbours(3);
    if (n.size() < 2) {
      run.ending = EdgeEnding::open;
      break;
    }
    if (n[0].range < c.clearance_mm) {
      run.ending = EdgeEnding::blocked;
      break;
    }
    // The third marble recedes while the robot leaves the start and approaches near the next
    // place, where the triple of the next place has taken over: climb only then, or the climb
    // would fall back to the start.
    const double gap = third_range(robot.last_scan()) - n[0].range;
    const bool approaching = gap < last_gap;
    last_gap = gap;
    if (approaching && gap < c.arrival_gap_mm) {
      const Climb climb = climb_to_place(robot);
      run.moves.push_back(climb.moved);
      run.displacement += climb.moved;
      if (climb.ending == ClimbEnding::place && run.displacement.norm() < 1 && !retried) {
        // Fell back to the start (an edge between nearly co-circular marbles, where the gap hardly
        // changes): go on past where the climb began and try once more.
        retried = true;
        last_gap = 0;
        const Eigen::Vector2d ahead = (run.length + c.step_mm) * robot.tool_direction(heading_deg);
        if (!step(ahead)) {
          run.ending = EdgeEnding::blocked;
          break;
        }
        continue;
      }
      run.ending = climb.ending == ClimbEnding::place       ? EdgeEnding::arrived
                   : climb.ending == ClimbEnding::too_close ? EdgeEnding::blocked
                                                            : EdgeEnding::open;
      break;
    }
    if (run.length >= c.max_edge_mm) {
      run.ending = EdgeEnding::open;
      break;
    }
    const Eigen::Vector2d normal = n[0].away - n[1].away;
    if (normal.norm() < 1e-3) {
      run.ending = EdgeEnding::open;
      break;
    }
    Eigen::Vector2d tangent = perpendicular(normal).normalized();
    if (tangent.dot(t) < 0) tangent = -tangent;
    Eigen::Vector2d correction = -(n[0].range - n[1].range) * normal / normal.squaredNorm();
    if (correction.norm() > c.step_mm) correction *= c.step_mm / correction.norm();
    t = tangent;
    if (!step(c.step_mm * tangent + correction)) {
      run.ending = EdgeEnding::blocked;
      break;
    }
    run.length += c.step_mm;
  }
  run.arrival_heading_deg = robot.compass_heading(t);
  run.dtheta_deg = wrap180(run.arrival_heading_deg - heading_deg);
  return run;
}

Climb retrace(Robot& robot, const EdgeRun& run) {
  for (const Eigen::Vector2d& move : std::ranges::reverse_view(run.moves)) robot.move(-move);
  return climb_to_place(robot);
}

}  // namespace neopipe::nav::nx
