#include "nav/mapmaker/reliability.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "nav/mapmaker/normal.hpp"

namespace neopipe::nav::mapmaker {
namespace {

// Beyond this many standard deviations a bound changes R by less than 3e-7: not worth a look.
constexpr double kReach = 5.0;

// The offset scan for rivals: steps over [0, reach] on each side (reach / 48 is under 0.3 mm at
// sigma 1.5), then halvings of the step that changes the winner (to 1e-4 of it).
constexpr int kScanSteps = 48;
constexpr int kBisections = 14;

// neopipe_reliability_fit --trials 4000 --seed 1 (docs/navigation.md has the table and the errors).
constexpr double kFittedLogK = 0.478903;
constexpr double kFittedBeta = 1.075169;
constexpr double kFittedGamma = 1.011016;

// scripts/fit_recovery_credit.py on `neopipe nav --trials` runs (docs/navigation.md says which).
constexpr double kRecoveredShare = 0.71;

struct OffsetBound {
  double slide;  ///< where along the slide
  double limit;  ///< the offset across the track that must not be crossed
  bool below;    ///< success needs offset < limit (else offset > limit)
};

// E f(Z) for Z ~ N(0, 1) by the midpoint rule on [-6, 6]: the integrands are bounded step-like
// functions of Z (an interval's probability), for which more nodes beat a higher-order rule.
struct NormalQuadrature {
  std::vector<double> nodes, weights;
};

// Nodes over e: the soft bounds make its integrand smooth on the scale of its own sd.
constexpr int kCoarseNodes = 24;

NormalQuadrature normal_quadrature(int nodes = 64) {
  constexpr double kSpan = 6.0;
  NormalQuadrature q;
  double total = 0;
  for (int k = 0; k < nodes; ++k) {
    const double x = -kSpan + (k + 0.5) * 2 * kSpan / nodes;
    q.nodes.push_back(x);
    q.weights.push_back(std::exp(-x * x / 2));
    total += q.weights.back();
  }
  for (double& w : q.weights) w /= total;
  return q;
}

// What the navigator sees at the start decides what may enter: the window's placement error can
// put a goal that enters early already in view (then it is not seen entering), or move an object of
// the view just outside the leading edges (then it enters first). Along each axis of travel the edge
// moves by a normal error of sd sigma; these events are taken as independent of the offset above.
double start_view_agrees(const WorldViews& views, const Trajectory& trajectory, const Eigen::Vector2d& heading,
                         const Eigen::Vector2d& start, double sigma) {  // NOLINT(bugprone-easily-swappable-parameters)
  if (!(sigma > 0)) return 1.0;
  const double a = views.window().side;
  // Depth of p inside the window behind the leading edge of each axis (negative: ahead of it).
  const auto depth = [&](const Eigen::Vector2d& p, int axis) {
    return heading[axis] > 0 ? start[axis] + a - p[axis] : p[axis] - start[axis];
  };
  double agrees = 1.0;
  const Eigen::Vector2d& goal = views.position(trajectory.to);
  sigma *= std::numbers::sqrt2;  // an object's place relative to the reference: both carry the survey's error
  for (int axis = 0; axis < 2; ++axis) {
    if (heading[axis] == 0) continue;
    const double ahead = -depth(goal, axis);  // > 0 on the axis the goal enters by
    if (ahead > 0 && ahead < kReach * sigma) agrees *= normal_cdf(ahead / sigma);
  }
  for (const std::uint32_t id : views.visible(trajectory.from)) {
    if (id == trajectory.from.object || id == trajectory.via) continue;  // known: never taken for the goal
    for (int axis = 0; axis < 2; ++axis) {
      if (heading[axis] == 0) continue;
      const double d = depth(views.position(id), axis);
      if (d < kReach * sigma) agrees *= normal_cdf(d / sigma);
    }
  }
  return agrees;
}

}  // namespace

double SelectionReliabilityModel::operator()(int visible, double relative_sigma) const {
  if (visible <= 2 || !(relative_sigma > 0)) return 1.0;
  const double log_odds = log_k + beta * std::log(visible - 2.0) + gamma * std::log(relative_sigma);
  return 1.0 / (1.0 + std::exp(log_odds));
}

RecoveryCredit RecoveryCredit::fitted() {
  return {kRecoveredShare};
}

SelectionReliabilityModel fitted_selection_model() {
  return {kFittedLogK, kFittedBeta, kFittedGamma};
}

double selection_reliability(int visible, double sigma, double window_side) {
  return fitted_selection_model()(visible, sigma / window_side);
}

double distance_rank_reliability(const WorldViews& views, const Placement& from, Description description,
                                 double sigma) {
  const auto chosen = views.landmark(from, description);
  if (!chosen || !(sigma > 0)) return 1.0;
  const double sign = description == Description::Near ? -1.0 : 1.0;  // which way the others must stay
  const Eigen::Vector2d& reference = views.position(from.object);
  const Eigen::Vector2d to_chosen = views.position(*chosen) - reference;
  const Eigen::Vector2d u_chosen = to_chosen.normalized();
  const double a = views.window().side;
  const Eigen::Vector2d origin = views.origin(from);
  const double reach = kReach * std::numbers::sqrt2 * sigma;
  struct Object {
    Eigen::Vector2d at;  ///< in the surveyed window
    Eigen::Vector2d u;   ///< unit vector from the reference
    double gap;          ///< how much farther the landmark is than this object, on the survey
  };
  std::vector<Object> rivals;
  const Eigen::Vector2d widen(reach, reach);
  views.grid().for_each_near(origin - widen, origin + Eigen::Vector2d(a, a) + widen, [&](std::uint32_t id) {
    if (id == from.object || id == *chosen) return;
    const Eigen::Vector2d q = views.position(id) - origin;
    if (std::min({q.x(), a - q.x(), q.y(), a - q.y()}) <= -reach) return;
    const Eigen::Vector2d to_rival = views.position(id) - reference;
    rivals.push_back({q, to_rival.normalized(), to_chosen.norm() - to_rival.norm()});
  });
  // The reference's error e_r moves the window and every distance at once, so the events "rival j
  // is in view and beats the landmark" go together: they are independent only given e_r, which is
  // integrated over. Given e_r, an object is in view when its own error keeps it inside all four
  // edges (one past a corner must cross two), and the gap to rival j, moved by (u_j - u_t).e_r, is
  // off by u_t.e_t - u_j.e_j, sd sqrt 2 sigma.
  static const NormalQuadrature quadrature = normal_quadrature(kCoarseNodes);
  const auto in_view = [&](const Eigen::Vector2d& q) {
    return normal_cdf(q.x() / sigma) * normal_cdf((a - q.x()) / sigma) * normal_cdf(q.y() / sigma) *
           normal_cdf((a - q.y()) / sigma);
  };
  const double gap_sd = std::numbers::sqrt2 * sigma;
  const Eigen::Vector2d chosen_at = views.position(*chosen) - origin;
  double held = 0;
  for (std::size_t i = 0; i < quadrature.nodes.size(); ++i) {
    for (std::size_t k = 0; k < quadrature.nodes.size(); ++k) {
      const Eigen::Vector2d e_r = sigma * Eigen::Vector2d(quadrature.nodes[i], quadrature.nodes[k]);
      double clear = in_view(chosen_at - e_r);  // the landmark itself stays in view
      for (const Object& j : rivals) {
        const double gap = j.gap + (j.u - u_chosen).dot(e_r);
        clear *= 1 - in_view(j.at - e_r) * normal_cdf(-sign * gap / gap_sd);
      }
      held += quadrature.weights[i] * quadrature.weights[k] * clear;
    }
  }
  return std::min(held, 1.0);  // the weights sum to 1 only up to rounding
}

double trajectory_reliability(const WorldViews& views, const Trajectory& trajectory, const NavigatorErrors& errors) {
  const Eigen::Vector2d heading = trajectory.heading(views);
  const Eigen::Vector2d across(-heading.y(), heading.x());
  const Eigen::Vector2d start = views.origin(trajectory.from);
  const double baseline = (views.position(trajectory.via) - views.position(trajectory.from.object)).norm();
  // Across the track the slide is off by d(s) = e c(s) + s g at distance s: e ~ N(0, sigma^2) is
  // the reference's survey error. It moves the window by e and turns the direction by -e/L towards
  // the landmark (Trajp), +e/L away from it (Trajn), so c(s) = 1 - s/L on Trajp (the two cancel near
  // the landmark) and 1 + s/L on Trajn (they add). g ~ N(0, sigma_g^2) is the landmark's error over
  // the baseline plus the motion's heading error, lumped at the goal's distance as the Monte Carlo
  // model does.
  const double towards = trajectory.direction == Direction::positive ? 1.0 : -1.0;
  const double sigma = errors.sigma;
  const double motion = std::hypot(errors.translation_per_mm, errors.rotation_per_mm * trajectory.slide / 2);
  const double sigma_g = std::hypot(sigma / baseline, motion);
  const auto c = [&](double s) { return 1 - towards * s / baseline; };
  const auto sd = [&](double s) { return std::hypot(sigma * c(s), s * sigma_g); };
  // With the objects' own errors (below): the widest spread of an object's offset from the track.
  const double widest = std::hypot(std::max(sd(0), sd(trajectory.slide)), sigma);
  if (!(widest > 0)) return 1.0;

  // The band the window sweeps, across the track.
  const double a = views.window().side;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& corner : std::array<Eigen::Vector2d, 4>{
           {Eigen::Vector2d(0, 0), Eigen::Vector2d(a, 0), Eigen::Vector2d(0, a), Eigen::Vector2d(a, a)}}) {
    const double w = across.dot(start + corner);
    lo = std::min(lo, w);
    hi = std::max(hi, w);
  }
  // Conditions for success, each d(s) < limit (below) or d(s) > limit: the goal stays in the band...
  const double w_goal = across.dot(views.position(trajectory.to));
  std::vector<OffsetBound> bounds{{trajectory.slide, w_goal - lo, true}, {trajectory.slide, w_goal - hi, false}};
  // ...and no other object enters before the goal. Whether one does is a step-like function of the
  // offset: scanned outwards from 0 on each side, the first offset at which it wins (refined by
  // bisection) is its bound. Scanning the real entry distances, not a linearisation, catches objects
  // that pass a trailing corner in the survey and enter by an edge when the window is a little off.
  // Objects are found in segments as first_entering does, widened by the reach of the largest
  // offset, each scanned once (its bound is softened by its own error: twice would count it twice).
  const ObjectGrid& grid = views.grid();
  const std::span<const Eigen::Vector2d> objects = grid.objects();
  const double reach = kReach * widest;
  const Eigen::Vector2d widen(a + reach, a + reach);
  const double behind = trajectory.slide + std::numbers::sqrt2 * a;  // a later entry cannot overtake
  const Eigen::Vector2d goal = views.position(trajectory.to);
  const auto entry = [&](double shift, const Eigen::Vector2d& p) {
    return entry_distance(views.window(), start + shift * across, heading, p);
  };
  // At offset d: does p enter before the goal? Unknown (nullopt) once the goal no longer enters:
  // the goal's own bounds above end the scan there.
  const auto wins = [&](double d, const Eigen::Vector2d& p) -> std::optional<bool> {
    const auto g = entry(d, goal);
    if (!g) return std::nullopt;
    const auto t = entry(d, p);
    return t && *t < *g;
  };
  const auto scan = [&](const Eigen::Vector2d& p, double side) {
    double inside = 0;  // the goal first here
    for (int k = 1; k <= kScanSteps; ++k) {
      const double d = side * reach * k / kScanSteps;
      const auto w = wins(d, p);
      if (!w) return;
      if (!*w) {
        inside = d;
        continue;
      }
      double outside = d;
      for (int i = 0; i < kBisections; ++i) {
        const double mid = (inside + outside) / 2;
        (wins(mid, p).value_or(false) ? outside : inside) = mid;
      }
      const double at = (inside + outside) / 2;
      bounds.push_back({entry(at, goal).value_or(trajectory.slide), at, side > 0});
      return;
    }
  };
  std::vector<std::uint32_t> near;
  for (double t0 = 0; t0 < behind; t0 += grid.cell()) {
    const double t1 = std::min(t0 + grid.cell(), behind);
    const Eigen::Vector2d p0 = start + t0 * heading, p1 = start + t1 * heading;
    grid.for_each_near(p0.cwiseMin(p1) - Eigen::Vector2d(reach, reach), p0.cwiseMax(p1) + widen,
                       [&](std::uint32_t id) { near.push_back(id); });
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (const std::uint32_t id : near) {
    // The reference and the direction's landmark are known to the navigator: never taken for the goal.
    if (id == trajectory.to || id == trajectory.from.object || id == trajectory.via) continue;
    scan(objects[id], 1.0);
    scan(objects[id], -1.0);
  }

  // Each bound's object (the goal too) sits where the survey put it only to within its own error,
  // across the track N(0, sigma^2) and independent of the others': the bound softens into the
  // probability that the object's own error does not carry it across. R integrates the product
  // over g and e (two quadratures over their normal laws).
  static const NormalQuadrature rule = normal_quadrature();
  static const NormalQuadrature coarse = normal_quadrature(kCoarseNodes);
  double reliability = 0;
  for (std::size_t k = 0; k < rule.nodes.size(); ++k) {
    const double g = sigma_g * rule.nodes[k];
    double given_g = 0;
    for (std::size_t j = 0; j < coarse.nodes.size(); ++j) {
      const double e = sigma * coarse.nodes[j];
      double p = coarse.weights[j];
      for (const OffsetBound& b : bounds) {
        // Success needs e c + s g < limit + own (below) or > limit + own, own ~ N(0, sigma^2).
        const double margin = b.limit - (e * c(b.slide) + b.slide * g);
        p *= sigma > 0 ? normal_cdf((b.below ? margin : -margin) / sigma) : ((b.below ? margin : -margin) > 0 ? 1 : 0);
        if (p < 1e-15) break;
      }
      given_g += p;
    }
    reliability += rule.weights[k] * given_g;
  }
  return std::clamp(reliability * start_view_agrees(views, trajectory, heading, start, sigma), 0.0, 1.0);
}

}  // namespace neopipe::nav::mapmaker
