#pragma once
// A small arithmetic expression language for filling look-up tables from a graph spec:
//   lut:  "255 - a"          lut2: "(a + 7*b + 4) / 8"        "a > b ? a - b : 0"
// Numbers, the declared variables, + - * / % ^ (power), comparisons (< <= > >= == != give 1 or 0),
// && || !, c ? x : y, parentheses, and the functions abs, min, max, clamp(x, lo, hi), floor, ceil,
// round, sqrt, exp, log, pow. Evaluated in double precision.

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace neopipe::pipeline {

class ExprError : public std::runtime_error {
 public:
  ExprError(const std::string& message, size_t column) : std::runtime_error(message), column_(column) {}
  /// 1-based position in the expression text.
  size_t column() const { return column_; }

 private:
  size_t column_;
};

class Expr {
 public:
  /// Throws ExprError on a syntax error or an unknown name.
  static Expr parse(std::string_view text, const std::vector<std::string>& variables);
  double eval(std::span<const double> values) const;

  struct Node;

 private:
  std::shared_ptr<const Node> root_;
};

/// An expression's value as a pixel: rounded to nearest (halves away from zero) and saturated to
/// 0..255; NaN becomes 0.
int to_pixel(double v);

}  // namespace neopipe::pipeline
