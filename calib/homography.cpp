#include "calib/homography.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "calib/cross2.hpp"

namespace neopipe::calib {
namespace {

// Geometric tests are relative to the point set's spread (RMS distance from its centroid), so they
// mean the same in pixels and in millimetres. 1e-9 is far below any detector's precision and far
// above double rounding: below it a configuration is degenerate for every practical purpose.
constexpr double kCoincidentTolerance = 1e-9;
constexpr double kCollinearTolerance = 1e-9;
// In Hartley-normalised coordinates the DLT matrix is well scaled, so a second-smallest singular
// value this far below the largest means a two-dimensional null space: no unique homography.
constexpr double kRankTolerance = 1e-12;
// Relative size below which a determinant (of the unit-norm normalised H) or an entry (H(2,2) against
// |H|) counts as 0: a singular map, or one that sends the pixel origin to infinity.
constexpr double kSingularTolerance = 1e-12;

enum class Plane { image, world };

const Eigen::Vector2d& coordinates(const Correspondence& c, Plane plane) {
  return plane == Plane::image ? c.pixel : c.world;
}

const char* plane_name(Plane plane) {
  return plane == Plane::image ? "in the image" : "in the world plane";
}

/// Centroid and RMS distance from it: the scale the tolerances are relative to.
struct Spread {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double rms = 0;
};

Spread spread_of(std::span<const Correspondence> points, Plane plane) {
  Spread s;
  for (const Correspondence& c : points) s.centroid += coordinates(c, plane);
  s.centroid /= static_cast<double>(points.size());
  double sum = 0;
  for (const Correspondence& c : points) sum += (coordinates(c, plane) - s.centroid).squaredNorm();
  s.rms = std::sqrt(sum / static_cast<double>(points.size()));
  return s;
}

/// Hartley's similarity: centroid to the origin, mean distance from it sqrt(2). With both point sets
/// normalised the DLT's algebraic error no longer depends on where the pixel and world origins are
/// or on the units (the fit is invariant to similarities of either frame), and the DLT matrix's
/// entries are all of order 1 instead of ranging from 1 to (pixel * mm).
Eigen::Matrix3d hartley_normalisation(std::span<const Correspondence> points, Plane plane) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Correspondence& c : points) centroid += coordinates(c, plane);
  centroid /= static_cast<double>(points.size());
  double mean_distance = 0;
  for (const Correspondence& c : points) mean_distance += (coordinates(c, plane) - centroid).norm();
  mean_distance /= static_cast<double>(points.size());
  const double s = mean_distance > 0 ? std::sqrt(2.0) / mean_distance : 1.0;
  Eigen::Matrix3d t;
  t << s, 0, -s * centroid.x(), 0, s, -s * centroid.y(), 0, 0, 1;
  return t;
}

Eigen::Vector2d transform(const Eigen::Matrix3d& t, const Eigen::Vector2d& p) {
  // Only for similarities (third row 0 0 1): no division needed.
  return t.topLeftCorner<2, 2>() * p + t.topRightCorner<2, 1>();
}

/// The first pair of coincident points and how many points take part in some coincidence.
struct Coincidences {
  std::size_t count = 0;
  std::size_t first = 0;
  std::size_t second = 0;
};

Coincidences find_coincident(std::span<const Correspondence> points, Plane plane, double tolerance) {
  // Sort by x and compare each point with the following ones while x stays within tolerance:
  // O(n log n) for spread-out data instead of all pairs.
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return coordinates(points[a], plane).x() < coordinates(points[b], plane).x();
  });
  std::vector<bool> involved(points.size(), false);
  Coincidences found;
  bool have_pair = false;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Eigen::Vector2d& a = coordinates(points[order[i]], plane);
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const Eigen::Vector2d& b = coordinates(points[order[j]], plane);
      if (b.x() - a.x() > tolerance) break;
      if ((b - a).norm() > tolerance) continue;
      involved[order[i]] = involved[order[j]] = true;
      const std::pair<std::size_t, std::size_t> pair = std::minmax(order[i], order[j]);
      if (!have_pair || pair < std::pair(found.first, found.second)) {
        std::tie(found.first, found.second) = pair;
        have_pair = true;
      }
    }
  }
  found.count = static_cast<std::size_t>(std::count(involved.begin(), involved.end(), true));
  return found;
}

/// How many points lie within tolerance of the line through a and b.
std::size_t count_on_line(std::span<const Correspondence> points, Plane plane, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, double tolerance) {
  const Eigen::Vector2d direction = (b - a).normalized();
  return static_cast<std::size_t>(std::count_if(points.begin(), points.end(), [&](const Correspondence& c) {
    return std::abs(cross(direction, coordinates(c, plane) - a)) <= tolerance;
  }));
}

/// The most points on one line, when it is at least n - 1 (0 otherwise). A homography has 8 degrees
/// of freedom and any number of collinear points fix only 5 of them (the line's image and a 1-D
/// projectivity), so n - 1 collinear points plus one more give 7 at most: degenerate. If n - 1 of
/// n >= 4 points share a line, two of the first three do, so three candidate lines suffice.
std::size_t max_collinear_if_degenerate(std::span<const Correspondence> points, Plane plane, double tolerance) {
  std::size_t best = 0;
  constexpr std::array<std::pair<std::size_t, std::size_t>, 3> kCandidates{{{0, 1}, {0, 2}, {1, 2}}};
  for (const auto& [i, j] : kCandidates) {
    const Eigen::Vector2d& a = coordinates(points[i], plane);
    const Eigen::Vector2d& b = coordinates(points[j], plane);
    if ((b - a).norm() <= tolerance) continue;  // coincident points are reported separately
    best = std::max(best, count_on_line(points, plane, a, b, tolerance));
  }
  return best + 1 >= points.size() ? best : 0;
}

void check_count(std::span<const Correspondence> points, const char* who) {
  if (points.size() < 4)
    throw CalibrationError(fmt::format("{}: {} correspondences, need at least 4", who, points.size()));
}

void check_not_coincident(std::span<const Correspondence> points, const char* who) {
  for (const Plane plane : {Plane::image, Plane::world}) {
    const Coincidences c = find_coincident(points, plane, kCoincidentTolerance * spread_of(points, plane).rms);
    if (c.count == 0) continue;
    const Eigen::Vector2d& p = coordinates(points[c.first], plane);
    throw CalibrationError(fmt::format("{}: {} of {} points coincide {} (first #{} and #{} at ({}, {}) {})", who,
                                       c.count, points.size(), plane_name(plane), c.first, c.second, p.x(), p.y(),
                                       plane == Plane::image ? "px" : "mm"));
  }
}

/// Collinear configurations are degenerate for every subset too, so RANSAC checks them as well.
void check_not_collinear(std::span<const Correspondence> points, const char* who) {
  const std::size_t n = points.size();
  for (const Plane plane : {Plane::image, Plane::world}) {
    const double tolerance = kCollinearTolerance * spread_of(points, plane).rms;
    const std::size_t on_line = max_collinear_if_degenerate(points, plane, tolerance);
    if (on_line == n)
      throw CalibrationError(fmt::format("{}: all {} points are collinear {}", who, n, plane_name(plane)));
    if (on_line > 0) {
      throw CalibrationError(
          fmt::format("{}: {} of {} points are collinear {}; a homography needs 4 points with no 3 "
                      "collinear",
                      who, on_line, n, plane_name(plane)));
    }
  }
}

/// The normalised DLT without the configuration checks, for RANSAC's samples and consensus sets
/// (which may hold duplicates). Either a homography with H(2,2) = 1 or why there is none.
struct DltResult {
  std::optional<Eigen::Matrix3d> h;
  std::string failure;
};

DltResult solve_dlt(std::span<const Correspondence> points) {
  const Eigen::Matrix3d tp = hartley_normalisation(points, Plane::image);
  const Eigen::Matrix3d tw = hartley_normalisation(points, Plane::world);
  // Two rows per point from world x (H pixel) = 0; at least 9 rows so that the SVD always has a
  // ninth singular value (a zero row for the minimal case changes nothing).
  const Eigen::Index rows = std::max<Eigen::Index>(9, 2 * static_cast<Eigen::Index>(points.size()));
  Eigen::Matrix<double, Eigen::Dynamic, 9> a = Eigen::Matrix<double, Eigen::Dynamic, 9>::Zero(rows, 9);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d p = transform(tp, points[i].pixel);
    const Eigen::Vector2d w = transform(tw, points[i].world);
    const auto r = static_cast<Eigen::Index>(2 * i);
    a.row(r) << p.x(), p.y(), 1, 0, 0, 0, -w.x() * p.x(), -w.x() * p.y(), -w.x();
    a.row(r + 1) << 0, 0, 0, p.x(), p.y(), 1, -w.y() * p.x(), -w.y() * p.y(), -w.y();
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, Eigen::Dynamic, 9>> svd(a, Eigen::ComputeFullV);
  const Eigen::Matrix<double, 9, 1>& sigma = svd.singularValues();
  const double rank_ratio = sigma(7) / sigma(0);
  if (!(rank_ratio > kRankTolerance)) {
    return {std::nullopt, fmt::format("the {} points do not determine a homography (rank-deficient DLT system, "
                                      "singular value ratio {:.1e})",
                                      points.size(), rank_ratio)};
  }
  const Eigen::Matrix<double, 9, 1> v = svd.matrixV().col(8);
  Eigen::Matrix3d hn;
  hn << v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7), v(8);
  if (!(std::abs(hn.determinant()) > kSingularTolerance)) {
    return {std::nullopt, fmt::format("the {} points only fit a singular map (|det| {:.1e} of the normalised H)",
                                      points.size(), std::abs(hn.determinant()))};
  }
  Eigen::Matrix3d h = tw.inverse() * hn * tp;
  if (!(std::abs(h(2, 2)) > kSingularTolerance * h.norm())) {
    return {std::nullopt, "the fitted map sends pixel (0, 0) to infinity, so H(2,2) cannot be 1"};
  }
  h /= h(2, 2);
  return {h, {}};
}

/// Through apply() itself, so that "never worse" holds for the error as callers compute it, to the
/// last bit. A point mapped to infinity gives inf or NaN, which every comparison here treats as bad.
double squared_error(const Eigen::Matrix3d& h, const Correspondence& c) {
  return (apply(h, c.pixel) - c.world).squaredNorm();
}

double sum_squared_error(const Eigen::Matrix3d& h, std::span<const Correspondence> points) {
  double sum = 0;
  for (const Correspondence& c : points) sum += squared_error(h, c);
  return std::isnan(sum) ? std::numeric_limits<double>::infinity() : sum;
}

// --- Levenberg-Marquardt ---------------------------------------------------------------------

constexpr int kMaxLmIterations = 100;
constexpr double kLmStepTolerance = 1e-12;         // relative step size
constexpr double kLmImprovementTolerance = 1e-15;  // relative cost decrease of an accepted step
constexpr double kLmMaxDamping = 1e20;             // steps this damped are negligible: nothing left to gain

/// Normal equations J^T J and J^T r for the 8 entries h0..h7 of g (g(2,2) = 1) acting on
/// normalised pixels q, residuals s * (g(q) - world) (s: the world normalisation's scale).
struct NormalEquations {
  Eigen::Matrix<double, 8, 8> jtj = Eigen::Matrix<double, 8, 8>::Zero();
  Eigen::Matrix<double, 8, 1> jtr = Eigen::Matrix<double, 8, 1>::Zero();
};

Eigen::Matrix3d from_parameters(const Eigen::Matrix<double, 8, 1>& x) {
  Eigen::Matrix3d g;
  g << x(0), x(1), x(2), x(3), x(4), x(5), x(6), x(7), 1;
  return g;
}

double normalised_cost(const Eigen::Matrix3d& g, std::span<const Eigen::Vector2d> q,
                       std::span<const Eigen::Vector2d> w) {
  double cost = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Eigen::Vector3d m = g * q[i].homogeneous();
    // A point crossing the vanishing line would be mapped through infinity: never a better model.
    if (!(m.z() > 0)) return std::numeric_limits<double>::infinity();
    cost += (m.head<2>() / m.z() - w[i]).squaredNorm();
  }
  return cost;
}

NormalEquations normal_equations(const Eigen::Matrix3d& g, std::span<const Eigen::Vector2d> q,
                                 std::span<const Eigen::Vector2d> w) {
  NormalEquations ne;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double u = q[i].x();
    const double v = q[i].y();
    const Eigen::Vector3d m = g * q[i].homogeneous();
    const double inv_z = 1.0 / m.z();
    const double x = m.x() * inv_z;
    const double y = m.y() * inv_z;
    // d(x/z)/dh = (dx/dh - (x/z) dz/dh) / z, likewise for y: the analytic Jacobian of apply().
    Eigen::Matrix<double, 8, 1> jx;
    Eigen::Matrix<double, 8, 1> jy;
    jx << u * inv_z, v * inv_z, inv_z, 0, 0, 0, -x * u * inv_z, -x * v * inv_z;
    jy << 0, 0, 0, u * inv_z, v * inv_z, inv_z, -y * u * inv_z, -y * v * inv_z;
    const double rx = x - w[i].x();
    const double ry = y - w[i].y();
    ne.jtj.selfadjointView<Eigen::Lower>().rankUpdate(jx);
    ne.jtj.selfadjointView<Eigen::Lower>().rankUpdate(jy);
    ne.jtr += jx * rx + jy * ry;
  }
  ne.jtj = ne.jtj.selfadjointView<Eigen::Lower>();
  return ne;
}

// --- RANSAC ------------------------------------------------------------------------------------

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny generator with a fully specified output, so the same
/// seed draws the same samples with every compiler and standard library (std::uniform_int_distribution
/// is implementation-defined).
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, n) without modulo bias: reject the 2^64 mod n lowest outputs.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }

 private:
  std::uint64_t state_;
};

using Sample = std::array<std::size_t, 4>;

Sample draw_sample(SplitMix64& rng, std::size_t n) {
  Sample sample{};
  for (std::size_t k = 0; k < sample.size(); ++k) {
    bool repeated = true;
    while (repeated) {
      sample[k] = static_cast<std::size_t>(rng.below(n));
      repeated = std::find(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(k), sample[k]) !=
                 sample.begin() + static_cast<std::ptrdiff_t>(k);
    }
  }
  return sample;
}

/// A minimal sample is usable when no three of its points are (nearly) collinear in either plane and
/// every triangle keeps (or every triangle flips) its orientation. A homography scales a triangle's
/// signed area by det(H) / (z_a z_b z_c), so mixed orientations mean the model would send some of
/// the sample through the vanishing line: a real camera never sees that, so skip such samples early.
bool usable_sample(std::span<const Correspondence> points, const Sample& sample, double image_tolerance,
                   double world_tolerance) {
  constexpr std::array<std::array<std::size_t, 3>, 4> kTriples{{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  int orientation = 0;
  for (const auto& triple : kTriples) {
    int sign = 1;
    for (const Plane plane : {Plane::image, Plane::world}) {
      const double tolerance = plane == Plane::image ? image_tolerance : world_tolerance;
      const Eigen::Vector2d& a = coordinates(points[sample[triple[0]]], plane);
      const Eigen::Vector2d& b = coordinates(points[sample[triple[1]]], plane);
      const Eigen::Vector2d& c = coordinates(points[sample[triple[2]]], plane);
      const double base = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
      const double area = cross(b - a, c - a);
      // |area| / base is (at least) the height of the triangle over its longest side.
      if (!(std::abs(area) > tolerance * base)) return false;
      sign *= area > 0 ? 1 : -1;
    }
    if (orientation != 0 && sign != orientation) return false;
    orientation = sign;
  }
  return true;
}

/// Which points map within the threshold, their count, and the truncated squared error (MSAC's
/// score) to prefer the tighter of two models with equally many inliers.
struct Consensus {
  std::vector<bool> inlier;
  int count = 0;
  double score = std::numeric_limits<double>::infinity();
};

Consensus consensus_of(const Eigen::Matrix3d& h, std::span<const Correspondence> points, double threshold) {
  const double threshold_sq = threshold * threshold;
  Consensus c;
  c.inlier.resize(points.size());
  c.score = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double e = squared_error(h, points[i]);  // NaN compares false: an outlier
    c.inlier[i] = e < threshold_sq;
    c.count += c.inlier[i] ? 1 : 0;
    c.score += std::min(e, threshold_sq);
  }
  return c;
}

Correspondences subset(std::span<const Correspondence> points, const std::vector<bool>& keep) {
  Correspondences out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

/// Samples needed to draw one all-inlier sample with the given confidence: log(1 - p) / log(1 - w^4).
int required_iterations(int inliers, std::size_t n, double confidence, int cap) {
  const double all_inlier_sample = std::pow(static_cast<double>(inliers) / static_cast<double>(n), 4);
  if (all_inlier_sample >= 1) return 1;
  const double needed = std::log1p(-confidence) / std::log1p(-all_inlier_sample);
  return needed < cap ? std::max(1, static_cast<int>(std::ceil(needed))) : cap;
}

// Consecutive unusable draws before concluding that the data hold no usable sample at all.
constexpr int kMaxUnusableDraws = 1000;
// Rounds of "fit the consensus set, recompute the consensus" until the set stops changing.
constexpr int kMaxConsensusRounds = 10;

/// refine_homography from start (H(2,2) = 1): start itself when nothing better is found.
Eigen::Matrix3d levenberg_marquardt(const Eigen::Matrix3d& start, std::span<const Correspondence> points) {
  if (points.empty()) return start;

  // Optimise in Hartley-normalised coordinates: in pixels the Jacobian's columns differ by five to six
  // orders of magnitude (u X / z against 1 / z), squared in J^T J. Fixing g(2,2) = 1 there is safe
  // because g(2,2) is the projective depth of the pixels' centroid, never 0 for points all on one side
  // of the vanishing line. The world normalisation is a similarity, so its cost is the world cost
  // times a constant: the same minimiser, and the same map as fixing H(2,2) = 1 in pixels.
  const Eigen::Matrix3d tp = hartley_normalisation(points, Plane::image);
  const Eigen::Matrix3d tw = hartley_normalisation(points, Plane::world);
  std::vector<Eigen::Vector2d> q;
  std::vector<Eigen::Vector2d> w;
  q.reserve(points.size());
  w.reserve(points.size());
  for (const Correspondence& c : points) {
    q.push_back(transform(tp, c.pixel));
    w.push_back(transform(tw, c.world));
  }
  Eigen::Matrix3d g0 = tw * start * tp.inverse();
  if (!(std::abs(g0(2, 2)) > kSingularTolerance * g0.norm())) return start;
  g0 /= g0(2, 2);  // positive z at the centroid, so the points' z are positive where the model is sane
  Eigen::Matrix<double, 8, 1> x;
  x << g0(0, 0), g0(0, 1), g0(0, 2), g0(1, 0), g0(1, 1), g0(1, 2), g0(2, 0), g0(2, 1);

  double cost = normalised_cost(from_parameters(x), q, w);
  if (!std::isfinite(cost)) return start;  // some point sits beyond the vanishing line: no local model
  // Nielsen's damping schedule: lambda (relative to the curvature, see `scale`) shrinks smoothly after
  // a good step and grows geometrically (nu doubling) after each rejected one.
  double lambda = 1e-3;
  double nu = 2;
  for (int iteration = 0; iteration < kMaxLmIterations; ++iteration) {
    const NormalEquations ne = normal_equations(from_parameters(x), q, w);
    if (ne.jtr.isZero(0)) break;  // exact fit
    // Marquardt's scaling (lambda times the diagonal) keeps the step invariant to parameter units;
    // the floor keeps the system definite when a parameter has no curvature at all.
    const Eigen::Matrix<double, 8, 1> scale = ne.jtj.diagonal().cwiseMax(1e-12 * ne.jtj.diagonal().maxCoeff());
    bool accepted = false;
    bool converged = false;
    while (!accepted && !converged) {
      Eigen::Matrix<double, 8, 8> damped = ne.jtj;
      damped.diagonal() += lambda * scale;
      const Eigen::LDLT<Eigen::Matrix<double, 8, 8>> ldlt(damped);
      const Eigen::Matrix<double, 8, 1> step = ldlt.solve(-ne.jtr);
      if (ldlt.info() != Eigen::Success || !step.allFinite()) {
        lambda *= nu;
        nu *= 2;
        converged = !(lambda < kLmMaxDamping);
        continue;
      }
      if (step.norm() <= kLmStepTolerance * (x.norm() + kLmStepTolerance)) {
        converged = true;
        break;
      }
      const Eigen::Matrix<double, 8, 1> candidate = x + step;
      const double new_cost = normalised_cost(from_parameters(candidate), q, w);
      // Gain ratio: actual decrease over the decrease the linearised model predicted, which for the
      // cost |r|^2 and (J^T J + lambda D) step = -J^T r is step . (lambda D step - J^T r).
      const double predicted = step.dot(lambda * scale.cwiseProduct(step) - ne.jtr);
      const double rho = (cost - new_cost) / predicted;
      if (std::isfinite(new_cost) && new_cost < cost && rho > 0) {
        const double improvement = (cost - new_cost) / cost;
        x = candidate;
        cost = new_cost;
        lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2 * rho - 1, 3));
        nu = 2;
        accepted = true;
        converged = improvement <= kLmImprovementTolerance;
      } else {
        lambda *= nu;
        nu *= 2;
        converged = !(lambda < kLmMaxDamping);
      }
    }
    if (converged) break;
  }

  Eigen::Matrix3d refined = tw.inverse() * from_parameters(x) * tp;
  if (!(std::abs(refined(2, 2)) > kSingularTolerance * refined.norm())) return start;
  refined /= refined(2, 2);
  // Judge in the caller's units: the result is never worse than where it started.
  return sum_squared_error(refined, points) <= sum_squared_error(start, points) ? refined : start;
}

}  // namespace

Eigen::Vector2d apply(const Eigen::Matrix3d& h, const Eigen::Vector2d& p) {
  const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1);
  return q.head<2>() / q.z();
}

Eigen::Matrix3d fit_homography_dlt(const Correspondences& points) {
  constexpr const char* kWho = "homography DLT";
  check_count(points, kWho);
  // Coincident points first: they would also pass for collinear and hide the real cause.
  check_not_coincident(points, kWho);
  check_not_collinear(points, kWho);
  DltResult result = solve_dlt(points);
  if (!result.h) throw CalibrationError(fmt::format("{}: {}", kWho, result.failure));
  return *result.h;
}

Eigen::Matrix3d refine_homography(const Eigen::Matrix3d& initial, const Correspondences& points) {
  if (!(std::abs(initial(2, 2)) > kSingularTolerance * initial.norm())) {
    throw CalibrationError("homography refinement: the initial H(2,2) is 0; expected a map with H(2,2) = 1");
  }
  return levenberg_marquardt(initial / initial(2, 2), points);
}

HomographyFit fit_homography_ransac(const Correspondences& points, const RansacOptions& options) {
  constexpr const char* kWho = "homography RANSAC";
  if (!(options.inlier_mm > 0) || options.iterations < 1 || !(options.confidence > 0 && options.confidence < 1)) {
    throw CalibrationError(
        fmt::format("{}: bad options (inlier_mm {} must be > 0, iterations {} >= 1, confidence {} "
                    "in (0, 1))",
                    kWho, options.inlier_mm, options.iterations, options.confidence));
  }
  check_count(points, kWho);
  check_not_collinear(points, kWho);  // no subset could do better
  const std::size_t n = points.size();
  const double image_tolerance = kCollinearTolerance * spread_of(points, Plane::image).rms;
  const double world_tolerance = kCollinearTolerance * spread_of(points, Plane::world).rms;

  SplitMix64 rng(options.seed);
  std::optional<Eigen::Matrix3d> best_model;
  Consensus best;
  int needed = options.iterations;
  int unusable = 0;
  for (int iteration = 0; iteration < needed && unusable < kMaxUnusableDraws;) {
    const Sample sample = draw_sample(rng, n);
    std::optional<Eigen::Matrix3d> model;
    if (usable_sample(points, sample, image_tolerance, world_tolerance)) {
      const std::array<Correspondence, 4> minimal{points[sample[0]], points[sample[1]], points[sample[2]],
                                                  points[sample[3]]};
      model = solve_dlt(minimal).h;
    }
    if (!model) {
      ++unusable;
      continue;
    }
    unusable = 0;
    ++iteration;
    Consensus c = consensus_of(*model, points, options.inlier_mm);
    if (c.count > best.count || (c.count == best.count && c.score < best.score)) {
      best = std::move(c);
      best_model = model;
      needed = required_iterations(best.count, n, options.confidence, options.iterations);
    }
  }
  if (!best_model) {
    throw CalibrationError(
        fmt::format("{}: no usable 4-point sample among {} points in {} draws (coincident or "
                    "collinear points, or inconsistent orientations)",
                    kWho, n, kMaxUnusableDraws));
  }

  // Fit all of the consensus set (DLT, then the world-plane least squares), recompute which points it
  // explains and repeat until that set is stable, so the returned flags describe the returned map.
  HomographyFit fit;
  fit.image_to_world = *best_model;
  for (int round = 0; round < kMaxConsensusRounds; ++round) {
    const Correspondences consensus = subset(points, best.inlier);
    const DltResult dlt = solve_dlt(consensus);
    const Eigen::Matrix3d refined = refine_homography(dlt.h ? *dlt.h : fit.image_to_world, consensus);
    Consensus next = consensus_of(refined, points, options.inlier_mm);
    if (next.count < 4) break;  // the fit fell apart: keep the previous model and its flags
    fit.image_to_world = refined;
    const bool stable = next.inlier == best.inlier;
    best = std::move(next);
    if (stable) break;
  }
  fit.inlier = std::move(best.inlier);
  fit.inliers = best.count;
  return fit;
}

}  // namespace neopipe::calib
