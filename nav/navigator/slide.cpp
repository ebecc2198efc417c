// Trajectories (park-kender.md §4): the window slides along the line reference -> landmark (Trajp)
// or back (Trajn). The map-maker sweeps the window continuously and takes the first object to enter
// (mapmaker/trajectories.cpp); the navigator moves in steps, so it must not step over an object that
// only clips a corner of the window. It sees marbles cut by the border (Sighting::partial) up to
// about a radius beyond it, so with steps shorter than that every object is seen, inside or as a
// cap, before or as it enters: the navigator predicts each cap's entry along the slide and stops
// where the first one enters. Everything in view at the start is tracked by its predicted place and
// never counts as entering. Entries are judged in the exact window (the reference exactly at its
// corner, as the map-maker placed it), which moves with the real one. When the map says where the
// goal lies from the reference (SlideGoal), a newcomer is placed from the reference by the moves made
// since: one short of that place is passed by, one beyond it ends the slide (the goal went by).

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "nav/common/landmarks.hpp"
#include "nav/navigator/pilot.hpp"

namespace neopipe::nav::navigator::detail {
namespace {

// The slide distances (relative to now) during which a point now at `q` (exact-window coordinates)
// is strictly inside the window: it moves by -t u as the window moves by t u. Empty if never.
struct Interval {
  double lo = 0;
  double hi = 0;
};
std::optional<Interval> inside_during(const Eigen::Vector2d& q, const Eigen::Vector2d& u, double side) {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    if (u[k] == 0) {
      if (!(q[k] > 0 && q[k] < side)) return std::nullopt;
      continue;
    }
    const double t1 = (q[k] - side) / u[k];
    const double t2 = q[k] / u[k];
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
  }
  if (!(lo < hi)) return std::nullopt;
  return Interval{lo, hi};
}

// Matches what is seen to the known objects' predicted places; returns what matches none.
std::vector<Eigen::Vector2d> newcomers(const std::vector<Eigen::Vector2d>& seen, std::vector<Eigen::Vector2d>& known,
                                       double gate) {
  std::vector<char> matched(known.size(), 0);
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : seen) {
    std::optional<std::size_t> best;
    double best_d2 = gate * gate;
    for (std::size_t k = 0; k < known.size(); ++k) {
      const double d2 = (p - known[k]).squaredNorm();
      if (!matched[k] && d2 <= best_d2) {
        best = k;
        best_d2 = d2;
      }
    }
    if (best) {
      matched[*best] = 1;
      known[*best] = p;
    } else {
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace

std::optional<Failure> slide(Pilot& pilot, const Hold& hold, const Eigen::Vector2d& via, const MapEntry& entry,
                             int alternative, double offset, Eigen::Vector2d& found) {
  const NavigatorConfig& config = pilot.config();
  const Direction direction = entry.slide.value_or(Direction::positive);
  const double max_slide = std::min(config.max_slide, entry.slide_limit.value_or(config.max_slide));
  const double side = config.window.side;
  const Eigen::Vector2d line = via - hold.landmark;
  if (line.norm() == 0) return Failure{Ending::lost, "the trajectory's two landmarks coincide"};
  const Eigen::Vector2d u = direction == Direction::positive ? line.normalized() : Eigen::Vector2d(-line.normalized());
  const Eigen::Vector2d corner = config.window.corner_point(hold.corner);

  // Kept after they leave the window (until well past its edge), so one flickering at the trailing
  // edge is not taken for a newcomer.
  std::vector<Eigen::Vector2d> known = held_view(pilot.sighting(), hold, config.window, pilot.heading()).points;
  Eigen::Vector2d reference = hold.landmark;  // predicted place: ties are broken from it, as the map-maker does
  if (offset != 0) {
    // A neighbouring placement: the same slide with the window moved across the track first. What
    // is in view once it has moved is known, as at any start.
    const Eigen::Vector2d d = offset * Eigen::Vector2d(-u.y(), u.x());
    pilot.move_and_look(d);
    if (!pilot.moved()) return Failure{Ending::lost, "the arm cannot move the window beside the trajectory"};
    reference -= d;
    const Eigen::Rotation2Dd unturn(pilot.heading());
    known.clear();
    for (const Eigen::Vector2d& p : everything_seen(pilot.sighting())) {
      const Eigen::Vector2d q = corner + unturn * (p - hold.landmark);
      if ((q.array() > 0).all() && (q.array() < side).all()) known.push_back(p);
    }
  }
  // The direction's landmark is known whatever the view: it may lie just beyond an edge (taken from
  // there by the seek, or cut by the border), and the slide brings it in, but it is never the goal
  // (the map-maker's model does not count it).
  const Eigen::Vector2d via_now = via + (reference - hold.landmark);
  if (!nearest(known, via_now, tracking_gate(0))) known.push_back(via_now);
  double gate = tracking_gate(0);
  double slid = 0;
  double last_step = 0;
  int skip = alternative;
  const double heading0 = pilot.heading();
  // Where a newcomer seen at `p` lies from the reference, along the track and across it (to the
  // left), in the axes the slide began with (the window may have turned since).
  const auto place = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
    const Eigen::Vector2d rel = Eigen::Rotation2Dd(pilot.heading() - heading0) * (p - reference);
    return {rel.dot(u), rel.x() * -u.y() + rel.y() * u.x()};
  };
  // What to make of it: the goal, an object entering before it (passed by, as known), or one
  // entering after it, which says the goal went by beside the window.
  enum class Verdict : std::uint8_t { goal, before, after };
  const auto judge = [&](const Eigen::Vector2d& p) {
    if (!entry.slide_goal || !config.slide_goals) return Verdict::goal;
    const Eigen::Vector2d at = place(p);
    if (entry.slide_goal->admits(at.x(), at.y())) return Verdict::goal;
    return entry.slide_goal->passed(at.x()) ? Verdict::after : Verdict::before;
  };
  const auto went_by = [&](const Eigen::Vector2d& p) {
    return Failure{Ending::lost,
                   fmt::format("an object entered {:.0f} mm along the trajectory ({}), beyond its goal ({:.0f} +- "
                               "{:.0f} mm): the goal went by beside the window",
                               place(p).x(), trajectory_name(direction), entry.slide_goal->along,
                               entry.slide_goal->along_tolerance),
                   true};
  };
  for (;;) {
    // The exact window's coordinates (see held_view): it moves with the real one, axis-aligned.
    const Eigen::Rotation2Dd unturn(pilot.heading());
    const Eigen::Vector2d u_exact = unturn * u;
    const auto exact = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
      return corner + unturn * (p - hold.landmark);
    };
    const std::vector<Eigen::Vector2d> fresh = newcomers(everything_seen(pilot.sighting()), known, gate);
    // A newcomer inside entered during the last step; of several, the one that entered first.
    std::optional<Eigen::Vector2d> goal;
    double goal_entered = 0;
    for (const Eigen::Vector2d& p : fresh) {
      const auto when = inside_during(exact(p), u_exact, side);
      if (!when || when->lo > 0 || when->hi <= 0) continue;  // not inside now
      // Entries happen through the leading edges during the last step. Anything else unmatched is a
      // known object's ghost: a deep cap at the trailing edge, located too poorly to be matched.
      if (-when->lo > last_step + 1.0) continue;
      if (!goal || when->lo < goal_entered || (when->lo == goal_entered && preferred(reference, p, *goal))) {
        goal = p;
        goal_entered = when->lo;
      }
    }
    if (goal) {
      const Verdict verdict = judge(*goal);
      if (verdict == Verdict::after) return went_by(*goal);
      if (verdict == Verdict::goal && skip == 0) {
        found = *goal;
        return std::nullopt;
      }
      // Passed by, or a newcomer taken before and found wrong: it is known now, and the slide goes on.
      known.push_back(*goal);
      if (verdict == Verdict::goal) --skip;
      continue;
    }
    const double step = std::min(config.slide_step, max_slide - slid);
    if (step <= 0) break;
    // A cap that will enter within the next step: stop just inside its entry, where it is in view.
    std::optional<Eigen::Vector2d> next;
    Interval next_when;
    for (const Eigen::Vector2d& p : fresh) {
      const auto when = inside_during(exact(p), u_exact, side);
      if (!when || when->lo <= 0 || when->lo > step) continue;  // already gone by, or not yet
      if (!next || when->lo < next_when.lo || (when->lo == next_when.lo && preferred(reference, p, *next))) {
        next = p;
        next_when = *when;
      }
    }
    const double t = next ? next_when.lo + std::min(0.5, 0.5 * (next_when.hi - next_when.lo)) : step;
    const Eigen::Vector2d d = t * u;
    for (Eigen::Vector2d& p : known) p -= d;
    reference -= d;
    pilot.move_and_look(d);
    if (!pilot.moved()) {
      return Failure{Ending::lost, fmt::format("the arm cannot go further along the trajectory ({}) after {:.0f} mm",
                                               trajectory_name(direction), slid)};
    }
    slid += t;
    last_step = t;
    gate = tracking_gate(t);
    if (next) {
      const std::vector<Eigen::Vector2d> seen = everything_seen(pilot.sighting());
      if (const auto i = nearest(seen, *next - d, gate)) {
        const Verdict verdict = judge(seen[*i]);
        if (verdict == Verdict::after) return went_by(seen[*i]);
        if (verdict == Verdict::goal && skip == 0) {
          found = seen[*i];
          return std::nullopt;
        }
        known.push_back(seen[*i]);
        if (verdict == Verdict::goal) --skip;
      }
    }
    std::erase_if(known,
                  [&](const Eigen::Vector2d& p) { return (p.array() < -side).any() || (p.array() > 2 * side).any(); });
  }
  // With the goal's place known, nothing where it should be means it went by beside the window (or
  // the direction was wrong): the entry's next try, not the landmark before it, is in doubt.
  return Failure{Ending::lost,
                 fmt::format("slid {:.0f} mm along the trajectory ({}) without meeting an object", max_slide,
                             trajectory_name(direction)),
                 entry.slide_goal.has_value() && config.slide_goals};
}

}  // namespace neopipe::nav::navigator::detail
