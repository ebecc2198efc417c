#include "calib/marble_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace neopipe::calib {
namespace {

// The parameters, in this order.
enum Param : int { cx, cy, rad, sigma, level, slope_x, slope_y, dome, table, dark, shift_x, shift_y, kCount };
using Params = Eigen::Matrix<double, kCount, 1>;

double phi(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

// Gauss-Legendre nodes and weights on [-1, 1], 16 points (positive half; the rule is symmetric).
constexpr std::array<double, 8> kNodes{0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                       0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
constexpr std::array<double, 8> kWeights{0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                         0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                         0.0622535239386479, 0.0271524594117541};

struct Sample {
  Eigen::Vector2d p;
  double value = 0;
};

double gauss(double z) {
  return std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi);
}

// The model's gray level at pixel centre p. Along the line through the marble's centre and p (unit
// direction n, signed position v from the centre), the scene without blur is: for |v| < R the
// marble, Lambertian under a distant light: a level, a slope (the light's horizontal part) and a
// dome sqrt(1 - v^2/R^2) (its vertical part); beyond it the table, darker where the line crosses
// the shadow, a disk of the marble's size displaced by `shift`. Blur is taken along that line (the
// straight-edge approximation: rim and shadow edges are several blur widths long), so the marble's
// rim and the shadow's edge beside it are blurred together, as they are in a camera: every piece in
// closed form but the dome, which is integrated by Gauss-Legendre in the angle psi, v = R sin psi,
// where it is smooth.
double model(const Params& q, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - Eigen::Vector2d(q[cx], q[cy]);
  const double s = std::max(std::abs(q[sigma]), 0.05);
  const double r = q[rad];
  const double u = d.norm();
  const Eigen::Vector2d n = u > 1e-12 ? Eigen::Vector2d(d / u) : Eigen::Vector2d::UnitX();
  const auto mass = [&](double from, double to) {  // E[1 (from < v < to)], v ~ N(u, s^2)
    return to > from ? phi((to - u) / s) - phi((from - u) / s) : 0.0;
  };
  const double inside = mass(-r, r);
  const double moment = u * inside + s * (gauss((-r - u) / s) - gauss((r - u) / s));  // E[v 1 (|v| < R)]
  // Where the line crosses the shadow disk, outside the marble.
  double shaded = 0;
  const Eigen::Vector2d shift(q[shift_x], q[shift_y]);
  const double along = n.dot(shift);
  const double disc = along * along - shift.squaredNorm() + r * r;
  if (disc > 0) {
    const double v1 = along - std::sqrt(disc);
    const double v2 = along + std::sqrt(disc);
    shaded = mass(v1, std::min(v2, -r)) + mass(std::max(v1, r), v2);
  }
  const double slope = q[slope_x] * n.x() + q[slope_y] * n.y();
  double dome_part = 0;
  const double lo = std::asin(std::clamp((u - 6 * s) / r, -1.0, 1.0));
  const double hi = std::asin(std::clamp((u + 6 * s) / r, -1.0, 1.0));
  if (hi > lo) {
    const double mid = 0.5 * (hi + lo);
    const double half = 0.5 * (hi - lo);
    for (std::size_t k = 0; k < kNodes.size(); ++k) {
      for (const double side : {-1.0, 1.0}) {
        const double psi = mid + side * half * kNodes[k];
        const double c = std::cos(psi);
        dome_part += kWeights[k] * c * c * gauss((r * std::sin(psi) - u) / s);
      }
    }
    dome_part *= half * r / s;
  }
  return q[table] * (1 - inside) - std::abs(q[dark]) * shaded + q[level] * inside + slope * moment / r +
         q[dome] * dome_part;
}

// A soft prior on the radius: the marble's size in the image is known to a few percent, and the
// rim must not swell to swallow a shadow the model has not yet placed.
struct RadiusPrior {
  double radius = 0;
  double weight = 0;  ///< gray levels of residual per pixel of radius
};

double cost(const Params& q, const std::vector<Sample>& samples, const RadiusPrior& prior) {
  double c = 0;
  for (const Sample& s : samples) c += std::pow(model(q, s.p) - s.value, 2);
  return c + std::pow(prior.weight * (q[rad] - prior.radius), 2);
}

// Levenberg-Marquardt over the parameters `free` selects, with central-difference derivatives, on
// fixed-size normal equations (a parameter held fixed gets a unit row). Returns the final cost.
double levenberg_marquardt(Params& q, const std::vector<Sample>& samples, const RadiusPrior& prior,
                           const std::array<bool, kCount>& free, int max_iterations) {
  using Normal = Eigen::Matrix<double, kCount, kCount>;
  double current = cost(q, samples, prior);
  double lambda = 1e-3;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Normal a = Normal::Zero();
    Params g = Params::Zero();
    Params row;
    for (const Sample& sample : samples) {
      const double e = model(q, sample.p) - sample.value;
      for (int k = 0; k < kCount; ++k) {
        row[k] = 0;
        if (!free[static_cast<std::size_t>(k)]) continue;
        const double h = 1e-4 * std::max(1.0, std::abs(q[k]));
        Params plus = q;
        Params minus = q;
        plus[k] += h;
        minus[k] -= h;
        row[k] = (model(plus, sample.p) - model(minus, sample.p)) / (2 * h);
      }
      a.selfadjointView<Eigen::Lower>().rankUpdate(row);
      g += e * row;
    }
    // The prior's row: d(weight (r - r0)) / dr = weight.
    a(rad, rad) += prior.weight * prior.weight;
    g[rad] += prior.weight * prior.weight * (q[rad] - prior.radius);
    a = a.selfadjointView<Eigen::Lower>();
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Normal damped = a;
      for (int k = 0; k < kCount; ++k) {
        damped(k, k) = free[static_cast<std::size_t>(k)] ? a(k, k) * (1 + lambda) + 1e-9 : 1.0;
      }
      const Params step = damped.ldlt().solve(-g);
      const Params next = q + step;
      const double trial = cost(next, samples, prior);
      if (std::isfinite(trial) && trial < current) {
        const bool converged = current - trial < 1e-10 * current + 1e-12;
        q = next;
        current = trial;
        lambda = std::max(lambda / 3, 1e-9);
        improved = true;
        if (converged) return current;
      } else {
        lambda *= 4;
      }
    }
    if (!improved) break;
  }
  return current;
}

}  // namespace

std::optional<MarbleFit> fit_marble(const cv::Mat& gray, const Eigen::Vector2d& seed, double radius,
                                    const MarbleFitOptions& o) {
  if (gray.type() != CV_8UC1 || gray.empty() || !(radius > 0) || !std::isfinite(seed.x() + seed.y())) {
    return std::nullopt;
  }
  const double reach = o.patch * radius;
  const int x0 = static_cast<int>(std::floor(seed.x() - reach));
  const int x1 = static_cast<int>(std::ceil(seed.x() + reach));
  const int y0 = static_cast<int>(std::floor(seed.y() - reach));
  const int y1 = static_cast<int>(std::ceil(seed.y() + reach));
  if (x0 < 0 || y0 < 0 || x1 >= gray.cols || y1 >= gray.rows) return std::nullopt;
  std::vector<Sample> samples;
  std::vector<double> ring;    // the patch's outer pixels: the table's level
  std::vector<double> centre;  // its inner ones: the marble's
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d p(x, y);
      const double u = (p - seed).norm();
      if (u > reach) continue;
      const double v = gray.at<std::uint8_t>(y, x);
      if (u < 0.5 * radius) centre.push_back(v);
      // The middle of the marble holds its highlight, which no smooth shading explains and which
      // says nothing about where the rim is: it is left out of the fit.
      if (u < o.hole * radius) continue;
      samples.push_back({p, v});
      if (u > 0.85 * reach) ring.push_back(v);
    }
  }
  if (ring.empty() || centre.empty()) return std::nullopt;
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  Params q = Params::Zero();
  q[cx] = seed.x();
  q[cy] = seed.y();
  q[rad] = radius;
  q[sigma] = 0.8;
  q[table] = median(ring);
  q[level] = 0.7 * median(centre);
  q[dome] = 0.3 * median(centre);
  if (q[level] - q[table] < 5) return std::nullopt;  // nothing bright to fit

  // First the marble on a flat table, then with its shadow started on the side away from the light
  // (the shading's slope points at it), kept only if it explains the pixels better.
  std::array<bool, kCount> free{};
  for (const int k : {cx, cy, rad, sigma, level, slope_x, slope_y, dome, table})
    free[static_cast<std::size_t>(k)] = true;
  const Params start = q;
  const RadiusPrior prior{radius, o.radius_weight};
  double best = levenberg_marquardt(q, samples, prior, free, o.max_iterations);
  const Eigen::Vector2d slope(q[slope_x], q[slope_y]);
  if (o.shadow && slope.norm() > 1e-6) {
    // Without a shadow in the model, the shadow's dark crescent drags the rim outwards on its side:
    // start again from the expected rim, with the shading just found and a shadow of moderate
    // darkness away from the light (the way the shading's slope does not point), at a few distances.
    Params found = q;
    for (const double distance : {0.15, 0.35, 0.6}) {
      Params with = start;
      for (const int k : {level, slope_x, slope_y, dome, table, sigma}) with[k] = found[k];
      const Eigen::Vector2d away = -distance * radius * slope.normalized();
      with[shift_x] = away.x();
      with[shift_y] = away.y();
      with[dark] = 0.4 * found[table];
      free[dark] = free[shift_x] = free[shift_y] = true;
      const double shadowed = levenberg_marquardt(with, samples, prior, free, o.max_iterations);
      if (shadowed < best && Eigen::Vector2d(with[shift_x], with[shift_y]).norm() < 1.5 * with[rad]) {
        q = with;
        best = shadowed;
      }
    }
  }
  if (!(q[rad] > 0.5 * radius && q[rad] < 2 * radius) || !((Eigen::Vector2d(q[cx], q[cy]) - seed).norm() < radius)) {
    return std::nullopt;
  }
  MarbleFit f;
  f.centre = {q[cx], q[cy]};
  f.radius = q[rad];
  f.blur = std::abs(q[sigma]);
  f.pixels = static_cast<int>(samples.size());
  f.rms = std::sqrt(best / static_cast<double>(samples.size()));
  return f;
}

}  // namespace neopipe::calib
