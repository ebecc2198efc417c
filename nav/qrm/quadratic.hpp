#pragma once
// Quadratic functions of up to four unknowns, kept both expanded (for evaluation and the exact lower
// bounds of spec qrm.md §5) and grouped as a sum of products of affine forms (for the interval bound
// of general quadratics, where a square of a difference stays an exact square).

#include <array>
#include <vector>

namespace neopipe::nav::qrm {

inline constexpr int kMaxUnknowns = 4;
using Point4 = std::array<double, kMaxUnknowns>;

/// An axis-aligned box; only the first n coordinates of a problem with n unknowns are used.
struct Box {
  Point4 lo{};
  Point4 hi{};
};

/// a . x + b.
struct Affine {
  Point4 a{};
  double b = 0;

  /// x_i.
  static Affine unknown(int i);
  static Affine constant(double b);
  Affine operator+(const Affine& o) const;
  Affine operator-(const Affine& o) const;
  Affine operator*(double k) const;
  bool operator==(const Affine&) const = default;
};

/// weight * l * m; when l == m the interval bound squares one interval (exact) instead of
/// multiplying two.
struct Product {
  double weight = 1;
  Affine l;
  Affine m;
};

/// Which lower bound a quadratic gets over a box (spec §5). The first three are exact minima.
enum class BoundKind {
  corners,     ///< linear or bilinear (no squared unknown): minimum over the box's corners
  separable,   ///< no cross terms: sum of 1-D minima
  one_square,  ///< one squared unknown: 1-D minimum in it at every corner of the others
  interval,    ///< anything else: interval arithmetic on the grouped form
};

class Quadratic {
 public:
  /// The sum of `products` in `unknowns` unknowns (1..4).
  Quadratic(int unknowns, std::vector<Product> products);

  int unknowns() const { return n_; }
  BoundKind bound_kind() const { return kind_; }
  /// -g.
  Quadratic negated() const;

  double operator()(const Point4& x) const;
  /// A lower bound of g over `box` (exact for the first three kinds, up to rounding).
  double lower_bound(const Box& box) const;
  /// The same bound by the code for any number of unknowns. lower_bound takes a path specialised
  /// for two unknowns (the measurement problems, most of the work of map building) that computes
  /// the same operations in the same order: a test holds the two equal bit for bit.
  double lower_bound_generic(const Box& box) const;

  /// Expanded coefficients: g = sum_i square(i) x_i^2 + sum_{i<j} cross(i,j) x_i x_j + linear(i) x_i + constant().
  double square(int i) const { return square_[i]; }
  double cross(int i, int j) const { return cross_[i][j]; }
  double linear(int i) const { return linear_[i]; }
  double constant() const { return constant_; }

 private:
  void expand();
  double corners_bound(const Box& box) const;
  double separable_bound(const Box& box) const;
  double one_square_bound(const Box& box) const;
  double interval_bound(const Box& box) const;
  double eval2(double x0, double x1) const;
  double corners_bound2(const Box& box) const;
  double one_square_bound2(const Box& box) const;
  double one_square_at(Point4 x, const Box& box) const;
  double one_square_at2(double other, const Box& box) const;

  int n_;
  std::vector<Product> products_;
  Point4 square_{};
  std::array<Point4, kMaxUnknowns> cross_{};  ///< upper triangle, i < j
  Point4 linear_{};
  double constant_ = 0;
  BoundKind kind_ = BoundKind::corners;
  int squared_unknown_ = -1;  ///< for one_square
  /// The unknowns g depends on: the corner bounds need only their corners (a composition problem's
  /// AB:C and AB:D constraints involve two of the four).
  std::array<int, kMaxUnknowns> active_{};
  int active_count_ = 0;
};

}  // namespace neopipe::nav::qrm
