#include "nav/qualnav/topology/productions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace neopipe::nav::qualnav {
namespace {

// An open interval of positions in the left-to-right order: −1 is the left end, n the right end.
// A point (the a specifier) has lo == hi == its position.
struct ProductionInterval {
  long lo = 0;
  long hi = 0;
  bool point = false;
};

long production_position(LandmarkId id, std::span<const LandmarkId> order, const HeadingSpecifier& s) {
  const auto it = std::find(order.begin(), order.end(), id);
  if (it == order.end()) {
    throw std::invalid_argument(std::string("heading production: ") + specifier_letter(s.kind) + "[" +
                                std::to_string(s.left) + " " + std::to_string(s.right) + "] names landmark " +
                                std::to_string(id) + ", which is not in the view");
  }
  return static_cast<long>(it - order.begin());
}

ProductionInterval production_interval(const HeadingSpecifier& s, std::span<const LandmarkId> order) {
  const long p = production_position(s.left, order, s);
  const long q = production_position(s.right, order, s);
  if (!(p < q || (s.kind == Specifier::a && p == q))) {
    throw std::invalid_argument(std::string("heading production: ") + specifier_letter(s.kind) + "[" +
                                std::to_string(s.left) + " " + std::to_string(s.right) + "] names " +
                                std::to_string(s.left) + ", which is not left of " + std::to_string(s.right));
  }
  const long n = static_cast<long>(order.size());
  switch (s.kind) {
    case Specifier::l:
      return {-1, p, false};
    case Specifier::b:
      return {p, q, false};
    case Specifier::r:
      return {q, n, false};
    case Specifier::a:
      return {p, p, true};
  }
  return {};
}

bool production_inside(long position, const ProductionInterval& in) {
  return in.lo < position && position < in.hi;
}

}  // namespace

char specifier_letter(Specifier s) {
  switch (s) {
    case Specifier::l:
      return 'l';
    case Specifier::b:
      return 'b';
    case Specifier::r:
      return 'r';
    case Specifier::a:
      return 'a';
  }
  return '?';
}

std::optional<HeadingSpecifier> produce(const HeadingSpecifier& x, const HeadingSpecifier& y,
                                        std::span<const LandmarkId> left_to_right) {
  const ProductionInterval ix = production_interval(x, left_to_right);
  const ProductionInterval iy = production_interval(y, left_to_right);
  if (ix.point && iy.point) return std::nullopt;  // a with a: the spec's "–"
  if (ix.point || iy.point) {
    // a[P Q] survives as a[P P] only when both landmarks of its pair lie inside the other interval.
    const HeadingSpecifier& a = ix.point ? x : y;
    const ProductionInterval& other = ix.point ? iy : ix;
    const long p = production_position(a.left, left_to_right, a);
    const long q = production_position(a.right, left_to_right, a);
    if (production_inside(p, other) && production_inside(q, other))
      return HeadingSpecifier{Specifier::a, a.left, a.left};
    return std::nullopt;
  }
  const long lo = std::max(ix.lo, iy.lo);
  const long hi = std::min(ix.hi, iy.hi);
  if (lo >= hi) return std::nullopt;
  const long n = static_cast<long>(left_to_right.size());
  const auto at = [&](long i) { return left_to_right[static_cast<std::size_t>(i)]; };
  if (lo == -1) {
    // (left end, X) → l[X Y], Y next right of X; X is never the rightmost (it is some pair's P).
    if (hi + 1 >= n) throw std::logic_error("heading production: (left end, rightmost) has no next landmark");
    return HeadingSpecifier{Specifier::l, at(hi), at(hi + 1)};
  }
  if (hi == n) {
    if (lo < 1) throw std::logic_error("heading production: (leftmost, right end) has no previous landmark");
    return HeadingSpecifier{Specifier::r, at(lo - 1), at(lo)};
  }
  return HeadingSpecifier{Specifier::b, at(lo), at(hi)};
}

std::optional<HeadingSpecifier> produce_all(std::span<const HeadingSpecifier> conjunction,
                                            std::span<const LandmarkId> left_to_right) {
  if (conjunction.empty()) throw std::invalid_argument("heading production: an empty conjunction");
  // A single specifier is checked against the order too.
  (void)production_interval(conjunction.front(), left_to_right);
  std::optional<HeadingSpecifier> result = conjunction.front();
  for (std::size_t i = 1; i < conjunction.size() && result; ++i)
    result = produce(*result, conjunction[i], left_to_right);
  return result;
}

std::optional<std::vector<LandmarkId>> left_to_right_order(std::span<const Sighting> seen) {
  constexpr double kTurn = 2 * std::numbers::pi;
  std::vector<Sighting> clockwise(seen.begin(), seen.end());
  for (Sighting& s : clockwise) {
    s.bearing = std::fmod(s.bearing, kTurn);
    if (s.bearing < 0) s.bearing += kTurn;
  }
  // Clockwise is decreasing counter-clockwise bearing; ties by id keep the order deterministic.
  std::sort(clockwise.begin(), clockwise.end(), [](const Sighting& a, const Sighting& b) {
    return a.bearing != b.bearing ? a.bearing > b.bearing : a.id < b.id;
  });
  for (std::size_t i = 1; i < clockwise.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (clockwise[i].id == clockwise[j].id) {
        throw std::invalid_argument("left_to_right_order: landmark " + std::to_string(clockwise[i].id) +
                                    " is seen twice");
      }
    }
  }
  std::vector<LandmarkId> order;
  if (clockwise.empty()) return order;
  // The gap after landmark i, clockwise to the next one (the last wraps to the first).
  std::size_t widest = 0;
  double widest_gap = -1;
  for (std::size_t i = 0; i < clockwise.size(); ++i) {
    const std::size_t next = (i + 1) % clockwise.size();
    double gap = clockwise[i].bearing - clockwise[next].bearing;
    if (next == 0) gap += kTurn;
    if (gap > widest_gap) {
      widest_gap = gap;
      widest = i;
    }
  }
  if (widest_gap < std::numbers::pi) return std::nullopt;
  for (std::size_t k = 1; k <= clockwise.size(); ++k) order.push_back(clockwise[(widest + k) % clockwise.size()].id);
  return order;
}

std::span<const std::string_view> production_orders() {
  static constexpr std::array<std::string_view, 6> kOrders{"ABCD", "ACBD", "ACDB", "CABD", "CDAB", "CADB"};
  return kOrders;
}

std::span<const Specifier> production_row_order() {
  static constexpr std::array<Specifier, 4> kRows{Specifier::r, Specifier::l, Specifier::b, Specifier::a};
  return kRows;
}

std::vector<ProductionCell> production_table() {
  // A, B, C, D are the landmark ids 0..3; a column's order lists them left to right.
  const auto letter = [](LandmarkId id) { return static_cast<char>('A' + id); };
  std::vector<ProductionCell> cells;
  for (const Specifier x : production_row_order()) {
    for (const Specifier y : production_row_order()) {
      for (const std::string_view column : production_orders()) {
        std::vector<LandmarkId> order;
        for (const char c : column) order.push_back(static_cast<LandmarkId>(c - 'A'));
        const std::optional<HeadingSpecifier> p = produce({x, 0, 1}, {y, 2, 3}, order);
        std::string text(kNoProduction);
        if (p) text = std::string{specifier_letter(p->kind), '[', letter(p->left), letter(p->right), ']'};
        cells.push_back({x, y, std::string(column), text});
      }
    }
  }
  return cells;
}

}  // namespace neopipe::nav::qualnav
