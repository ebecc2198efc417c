#include "nav/qrm/quadratic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace neopipe::nav::qrm {
namespace {

// Expanded coefficients whose contributions cancel (cos^2 + sin^2 - cos^2 - sin^2 in a measurement
// problem) are rounding noise, not a term: treating them as zero keeps the bound exact instead of
// falling back to intervals for a squared unknown that is not there.
constexpr double kCancellation = 1e-12;

struct Accumulator {
  double sum = 0;
  double magnitude = 0;
  void add(double v) {
    sum += v;
    magnitude += std::abs(v);
  }
  double value() const { return std::abs(sum) <= kCancellation * magnitude ? 0.0 : sum; }
};

// min of q t^2 + b t over [lo, hi].
double min_1d(double q, double b, double lo, double hi) {
  double best = std::min(lo * (q * lo + b), hi * (q * hi + b));
  if (q > 0) {
    const double t = -b / (2 * q);
    if (t > lo && t < hi) best = std::min(best, t * (q * t + b));
  }
  return best;
}

struct Interval {
  double lo;
  double hi;
};

Interval range_of(const Affine& f, const Box& box, int n) {
  Interval r{f.b, f.b};
  for (int i = 0; i < n; ++i) {
    const double u = f.a[i] * box.lo[i];
    const double v = f.a[i] * box.hi[i];
    r.lo += std::min(u, v);
    r.hi += std::max(u, v);
  }
  return r;
}

}  // namespace

// operator() for n = 2, term for term (inlined: the bounds call it at every corner of every box).
inline double Quadratic::eval2(double x0, double x1) const {
  double g = constant_;
  double row0 = square_[0] * x0 + linear_[0];
  row0 += cross_[0][1] * x1;
  g += row0 * x0;
  const double row1 = square_[1] * x1 + linear_[1];
  g += row1 * x1;
  return g;
}

Affine Affine::unknown(int i) {
  Affine f;
  f.a.at(i) = 1;
  return f;
}

Affine Affine::constant(double b) {
  Affine f;
  f.b = b;
  return f;
}

Affine Affine::operator+(const Affine& o) const {
  Affine f;
  for (int i = 0; i < kMaxUnknowns; ++i) f.a[i] = a[i] + o.a[i];
  f.b = b + o.b;
  return f;
}

Affine Affine::operator-(const Affine& o) const {
  return *this + o * -1.0;
}

Affine Affine::operator*(double k) const {
  Affine f;
  for (int i = 0; i < kMaxUnknowns; ++i) f.a[i] = a[i] * k;
  f.b = b * k;
  return f;
}

Quadratic::Quadratic(int unknowns, std::vector<Product> products) : n_(unknowns), products_(std::move(products)) {
  if (n_ < 1 || n_ > kMaxUnknowns) throw std::invalid_argument("a quadratic has 1 to 4 unknowns");
  expand();
}

void Quadratic::expand() {
  std::array<Accumulator, kMaxUnknowns> square;
  std::array<std::array<Accumulator, kMaxUnknowns>, kMaxUnknowns> cross;
  std::array<Accumulator, kMaxUnknowns> linear;
  Accumulator constant;
  for (const Product& p : products_) {
    for (int i = 0; i < n_; ++i) {
      for (int j = 0; j < n_; ++j) {
        const double v = p.weight * p.l.a[i] * p.m.a[j];
        if (i == j) {
          square[i].add(v);
        } else {
          cross[std::min(i, j)][std::max(i, j)].add(v);
        }
      }
      linear[i].add(p.weight * (p.l.a[i] * p.m.b + p.l.b * p.m.a[i]));
    }
    constant.add(p.weight * p.l.b * p.m.b);
  }
  int squares = 0;
  bool crosses = false;
  for (int i = 0; i < n_; ++i) {
    square_[i] = square[i].value();
    linear_[i] = linear[i].value();
    if (square_[i] != 0) {
      ++squares;
      squared_unknown_ = i;
    }
    for (int j = i + 1; j < n_; ++j) {
      cross_[i][j] = cross[i][j].value();
      crosses = crosses || cross_[i][j] != 0;
    }
  }
  constant_ = constant.value();
  for (int i = 0; i < n_; ++i) {
    bool used = square_[i] != 0 || linear_[i] != 0;
    for (int j = 0; j < n_; ++j) used = used || (j != i && cross_[std::min(i, j)][std::max(i, j)] != 0);
    if (used) active_[active_count_++] = i;
  }
  if (squares == 0) {
    kind_ = BoundKind::corners;
  } else if (!crosses) {
    kind_ = BoundKind::separable;
  } else if (squares == 1) {
    kind_ = BoundKind::one_square;
  } else {
    kind_ = BoundKind::interval;
  }
}

Quadratic Quadratic::negated() const {
  std::vector<Product> products = products_;
  for (Product& p : products) p.weight = -p.weight;
  return {n_, std::move(products)};
}

double Quadratic::operator()(const Point4& x) const {
  if (n_ == 2) return eval2(x[0], x[1]);
  double g = constant_;
  for (int i = 0; i < n_; ++i) {
    double row = square_[i] * x[i] + linear_[i];
    for (int j = i + 1; j < n_; ++j) row += cross_[i][j] * x[j];
    g += row * x[i];
  }
  return g;
}

double Quadratic::lower_bound(const Box& box) const {
  if (n_ == 2) {
    switch (kind_) {
      case BoundKind::corners:
        return corners_bound2(box);
      case BoundKind::separable:
        return separable_bound(box);
      case BoundKind::one_square:
        return one_square_bound2(box);
      case BoundKind::interval:
        return interval_bound(box);
    }
  }
  return lower_bound_generic(box);
}

// corners_bound for n = 2: the same corners (an unused unknown stays 0), so the same minimum.
double Quadratic::corners_bound2(const Box& box) const {
  if (active_count_ == 2) {
    return std::min(std::min(eval2(box.lo[0], box.lo[1]), eval2(box.hi[0], box.lo[1])),
                    std::min(eval2(box.lo[0], box.hi[1]), eval2(box.hi[0], box.hi[1])));
  }
  if (active_count_ == 0) return eval2(0, 0);
  if (active_[0] == 0) return std::min(eval2(box.lo[0], 0), eval2(box.hi[0], 0));
  return std::min(eval2(0, box.lo[1]), eval2(0, box.hi[1]));
}

// one_square_bound for n = 2: the other unknown at each end of its range (0 when g does not use
// it); one_square_at2 is one_square_at for two unknowns, in scalars.
double Quadratic::one_square_bound2(const Box& box) const {
  if (active_count_ == 1) return one_square_at2(0, box);
  const int o = 1 - squared_unknown_;
  return std::min(one_square_at2(box.lo[o], box), one_square_at2(box.hi[o], box));
}

[[gnu::noinline]] double Quadratic::one_square_at2(double other, const Box& box) const {
  const int k = squared_unknown_;
  double b = linear_[k];
  b += cross_[0][1] * other;
  const double g = k == 0 ? eval2(0, other) : eval2(other, 0);
  return g + min_1d(square_[k], b, box.lo[k], box.hi[k]);
}

double Quadratic::lower_bound_generic(const Box& box) const {
  switch (kind_) {
    case BoundKind::corners:
      return corners_bound(box);
    case BoundKind::separable:
      return separable_bound(box);
    case BoundKind::one_square:
      return one_square_bound(box);
    case BoundKind::interval:
      return interval_bound(box);
  }
  return interval_bound(box);
}

double Quadratic::corners_bound(const Box& box) const {
  double best = INFINITY;
  Point4 x{};  // unknowns g does not use stay 0: their coefficients are all zero
  for (unsigned corner = 0; corner < (1U << active_count_); ++corner) {
    for (int a = 0; a < active_count_; ++a) {
      const int i = active_[a];
      x[i] = ((corner >> a) & 1U) != 0 ? box.hi[i] : box.lo[i];
    }
    best = std::min(best, (*this)(x));
  }
  return best;
}

double Quadratic::separable_bound(const Box& box) const {
  double sum = constant_;
  for (int i = 0; i < n_; ++i) sum += min_1d(square_[i], linear_[i], box.lo[i], box.hi[i]);
  return sum;
}

double Quadratic::one_square_bound(const Box& box) const {
  const int k = squared_unknown_;
  double best = INFINITY;
  Point4 x{};
  // g is multilinear in the other unknowns for any fixed x_k, so its minimum lies at one of their
  // corners; along x_k it is a parabola.
  for (unsigned corner = 0; corner < (1U << (active_count_ - 1)); ++corner) {
    unsigned bit = 0;
    for (int a = 0; a < active_count_; ++a) {
      const int i = active_[a];
      if (i == k) continue;
      x[i] = ((corner >> bit++) & 1U) != 0 ? box.hi[i] : box.lo[i];
    }
    best = std::min(best, one_square_at(x, box));
  }
  return best;
}

// One corner of the unknowns other than x_k (x_k itself is ignored): g there with x_k = 0 plus the
// 1-D minimum along x_k. Never inlined, so that both bounds that use it round alike: with fused
// multiply-adds, inlining lets the compiler fuse this sum with the caller's arithmetic differently.
[[gnu::noinline]] double Quadratic::one_square_at(Point4 x, const Box& box) const {
  const int k = squared_unknown_;
  x[k] = 0;
  double b = linear_[k];
  for (int j = 0; j < n_; ++j) {
    if (j != k) b += cross_[std::min(j, k)][std::max(j, k)] * x[j];
  }
  return (*this)(x) + min_1d(square_[k], b, box.lo[k], box.hi[k]);
}

double Quadratic::interval_bound(const Box& box) const {
  double sum = 0;
  for (const Product& p : products_) {
    const Interval l = range_of(p.l, box, n_);
    Interval product{};
    if (p.l == p.m) {
      const double lo2 = l.lo * l.lo;
      const double hi2 = l.hi * l.hi;
      product = {(l.lo <= 0 && l.hi >= 0) ? 0.0 : std::min(lo2, hi2), std::max(lo2, hi2)};
    } else {
      const Interval m = range_of(p.m, box, n_);
      const double c1 = l.lo * m.lo;
      const double c2 = l.lo * m.hi;
      const double c3 = l.hi * m.lo;
      const double c4 = l.hi * m.hi;
      product = {std::min({c1, c2, c3, c4}), std::max({c1, c2, c3, c4})};
    }
    sum += p.weight >= 0 ? p.weight * product.lo : p.weight * product.hi;
  }
  return sum;
}

}  // namespace neopipe::nav::qrm
