// Tests of the look-up-table expression language (pipeline/expr.hpp): operator precedence and
// associativity (+ - * / % ^, unary - and !, comparisons, && ||, the right-associative ternary),
// every built-in function, variables bound by position, and syntax errors reported as ExprError
// with the 1-based column of the offending character. Also to_pixel, which turns an expression's
// value into a pixel: rounded to nearest with halves away from zero, saturated to 0..255, NaN -> 0.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pipeline/expr.hpp"

namespace pl = neopipe::pipeline;

namespace {

// Evaluates `text` with variables a and b bound to the given values.
double eval_ab(const std::string& text, double a = 0, double b = 0) {
  const std::vector<double> values{a, b};
  return pl::Expr::parse(text, {"a", "b"}).eval(values);
}

struct ParseFailure {
  std::string message;
  size_t column = 0;
};

// Parses `text` (variables a and b) expecting an ExprError; returns its message and column.
ParseFailure parse_failure(const std::string& text) {
  try {
    (void)pl::Expr::parse(text, {"a", "b"});
  } catch (const pl::ExprError& e) {
    return {e.what(), e.column()};
  }
  ADD_FAILURE() << "\"" << text << "\" parsed without error";
  return {};
}

}  // namespace

TEST(Expr, NumbersAndVariables) {
  EXPECT_EQ(eval_ab("42"), 42);
  EXPECT_EQ(eval_ab("1.5"), 1.5);
  EXPECT_EQ(eval_ab(".25"), 0.25);
  EXPECT_EQ(eval_ab("1e2"), 100);
  EXPECT_EQ(eval_ab("a", 7, 9), 7);
  EXPECT_EQ(eval_ab("b", 7, 9), 9);
  EXPECT_EQ(eval_ab("  a  +  b  ", 7, 9), 16);
  // Variables bind by their position in the declared list, whatever their names.
  const std::vector<double> v{1, 2, 3};
  EXPECT_EQ(pl::Expr::parse("x * 100 + y * 10 + zed", {"x", "y", "zed"}).eval(v), 123);
  EXPECT_EQ(pl::Expr::parse("nw + 2*c + 4*se", {"nw", "c", "se"}).eval(v), 1 + 4 + 12);
}

TEST(Expr, ArithmeticPrecedenceAndAssociativity) {
  EXPECT_EQ(eval_ab("1 + 2 * 3"), 7);
  EXPECT_EQ(eval_ab("(1 + 2) * 3"), 9);
  EXPECT_EQ(eval_ab("10 - 4 - 3"), 3);  // left-associative
  EXPECT_EQ(eval_ab("20 / 4 / 5"), 1);
  EXPECT_EQ(eval_ab("7 % 3"), 1);
  EXPECT_EQ(eval_ab("2 + 7 % 3 * 2"), 4);  // % binds like * and /
  EXPECT_EQ(eval_ab("7 / 2"), 3.5);        // double precision, no integer division
  EXPECT_EQ(eval_ab("2 ^ 10"), 1024);
  EXPECT_EQ(eval_ab("2 ^ 3 ^ 2"), 512);  // right-associative: 2^(3^2)
  EXPECT_EQ(eval_ab("2 * 3 ^ 2"), 18);   // ^ binds tighter than *
  EXPECT_EQ(eval_ab("-2 ^ 2"), -4);      // and tighter than unary minus
  EXPECT_EQ(eval_ab("2 ^ -1"), 0.5);
  EXPECT_EQ(eval_ab("2 * -3"), -6);
  EXPECT_EQ(eval_ab("--3"), 3);
  EXPECT_EQ(eval_ab("+3"), 3);
  EXPECT_EQ(eval_ab("(a + 7*b + 4) / 8", 8, 8), 8.5);
}

TEST(Expr, ComparisonsAndLogic) {
  EXPECT_EQ(eval_ab("1 < 2"), 1);
  EXPECT_EQ(eval_ab("2 < 2"), 0);
  EXPECT_EQ(eval_ab("2 <= 2"), 1);
  EXPECT_EQ(eval_ab("3 > 2"), 1);
  EXPECT_EQ(eval_ab("2 >= 3"), 0);
  EXPECT_EQ(eval_ab("3 == 3"), 1);
  EXPECT_EQ(eval_ab("3 != 3"), 0);
  EXPECT_EQ(eval_ab("1 + 1 > 1"), 1);         // arithmetic binds tighter than comparison
  EXPECT_EQ(eval_ab("1 < 2 == 1"), 1);        // comparisons chain left to right: (1 < 2) == 1
  EXPECT_EQ(eval_ab("0.1 + 0.2 == 0.3"), 0);  // plain double arithmetic
  EXPECT_EQ(eval_ab("!0"), 1);
  EXPECT_EQ(eval_ab("!5"), 0);
  EXPECT_EQ(eval_ab("!!5"), 1);
  EXPECT_EQ(eval_ab("2 && 3"), 1);
  EXPECT_EQ(eval_ab("2 && 0"), 0);
  EXPECT_EQ(eval_ab("0 || 0"), 0);
  EXPECT_EQ(eval_ab("0 || -1"), 1);
  EXPECT_EQ(eval_ab("1 && 0 || 1"), 1);  // && binds tighter than ||
  EXPECT_EQ(eval_ab("0 || 1 && 0"), 0);
  EXPECT_EQ(eval_ab("a != b", 3, 4), 1);
  EXPECT_EQ(eval_ab("a<-1", -2), 1);  // "<" followed by a unary minus, not an operator "<-"
}

TEST(Expr, Ternary) {
  EXPECT_EQ(eval_ab("a > b ? a - b : 0", 10, 3), 7);
  EXPECT_EQ(eval_ab("a > b ? a - b : 0", 3, 10), 0);
  // Right-associative: a ? 1 : (b ? 2 : 3).
  EXPECT_EQ(eval_ab("a ? 1 : b ? 2 : 3", 1, 1), 1);
  EXPECT_EQ(eval_ab("a ? 1 : b ? 2 : 3", 0, 1), 2);
  EXPECT_EQ(eval_ab("a ? 1 : b ? 2 : 3", 0, 0), 3);
  EXPECT_EQ(eval_ab("a ? b ? 1 : 2 : 3", 1, 0), 2);
  // The condition takes the whole || expression; the branches are full expressions.
  EXPECT_EQ(eval_ab("0 || 0 ? 5 : 6"), 6);
  EXPECT_EQ(eval_ab("1 ? 2 + 3 : 4 * 5"), 5);
  EXPECT_EQ(eval_ab("(1 ? 2 : 3) + 10"), 12);
}

TEST(Expr, Functions) {
  EXPECT_EQ(eval_ab("abs(-3)"), 3);
  EXPECT_EQ(eval_ab("abs(a - b)", 2, 9), 7);
  EXPECT_EQ(eval_ab("min(a, b)", 2, 9), 2);
  EXPECT_EQ(eval_ab("max(a, b)", 2, 9), 9);
  EXPECT_EQ(eval_ab("clamp(300, 0, 255)"), 255);
  EXPECT_EQ(eval_ab("clamp(-5, 0, 255)"), 0);
  EXPECT_EQ(eval_ab("clamp(17, 0, 255)"), 17);
  EXPECT_EQ(eval_ab("floor(-1.5)"), -2);
  EXPECT_EQ(eval_ab("floor(2.99)"), 2);
  EXPECT_EQ(eval_ab("ceil(1.2)"), 2);
  EXPECT_EQ(eval_ab("round(2.5)"), 3);
  EXPECT_EQ(eval_ab("round(-2.5)"), -3);
  EXPECT_EQ(eval_ab("sqrt(16)"), 4);
  EXPECT_EQ(eval_ab("exp(0)"), 1);
  EXPECT_EQ(eval_ab("log(1)"), 0);
  EXPECT_DOUBLE_EQ(eval_ab("log(exp(2))"), 2);
  EXPECT_EQ(eval_ab("pow(2, 10)"), 1024);
  EXPECT_EQ(eval_ab("max(min(a, 100), 10) + abs(b)", 500, -1), 101);
  EXPECT_EQ(eval_ab("floor((a + 3*b) / 4)", 1, 2), 1);
  EXPECT_EQ(eval_ab("min(1 ? 4 : 5, 3)"), 3);  // arguments are full expressions
}

TEST(Expr, DivisionByZeroFollowsIeee) {
  EXPECT_TRUE(std::isinf(eval_ab("1 / 0")));
  EXPECT_TRUE(std::isnan(eval_ab("0 / 0")));
  EXPECT_TRUE(std::isnan(eval_ab("sqrt(-1)")));
}

TEST(Expr, ParsedExpressionIsReusable) {
  const pl::Expr e = pl::Expr::parse("a * 2 + b", {"a", "b"});
  for (int a = 0; a < 5; ++a) {
    for (int b = 0; b < 5; ++b) {
      const std::vector<double> v{static_cast<double>(a), static_cast<double>(b)};
      EXPECT_EQ(e.eval(v), a * 2 + b);
    }
  }
  const pl::Expr copy = e;  // copies share the parsed tree
  const std::vector<double> v{10, 1};
  EXPECT_EQ(copy.eval(v), 21);
}

TEST(Expr, ErrorsCarryTheirColumn) {
  struct Case {
    const char* text;
    size_t column;
    const char* message_part;
  };
  const Case cases[] = {
      {"a +* 2", 4, "unexpected '*'"},
      {"a + ", 5, "unexpected end of expression"},
      {"", 1, "unexpected end of expression"},
      {"(a + 1", 7, "expected ')'"},
      {"1 2", 3, "unexpected '2'"},
      {"a $ b", 3, "unexpected '$'"},
      {"a = b", 3, "unexpected '='"},
      {"a | b", 3, "unexpected '|'"},
      {"x + 1", 1, "unknown name 'x'"},
      {"a + xy", 5, "unknown name 'xy'"},
      {"a + sqrt", 5, "unknown name 'sqrt'"},
      {"b + foo(a)", 5, "unknown function 'foo'"},
      {"1 + min(a)", 5, "min() takes 2 arguments"},
      {"abs()", 1, "abs() takes 1 argument"},
      {"clamp(a, 1)", 1, "clamp() takes 3 arguments"},
      {"max(a, b", 9, "expected ')' after the arguments of max"},
      {"a ? 1", 6, "expected ':'"},
      {"a ? 1 ; 2", 7, "expected ':'"},
      {"0x10 + a", 1, "bad number"},  // decimal numbers only
      {"2a", 1, "bad number"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    const ParseFailure f = parse_failure(c.text);
    EXPECT_EQ(f.column, c.column);
    EXPECT_NE(f.message.find(c.message_part), std::string::npos) << f.message;
  }
}

TEST(Expr, UnknownNameListsTheVariables) {
  const ParseFailure f = parse_failure("c");
  EXPECT_NE(f.message.find("(variables: a, b)"), std::string::npos) << f.message;
}

TEST(ToPixel, RoundsHalvesAwayFromZero) {
  EXPECT_EQ(pl::to_pixel(0.0), 0);
  EXPECT_EQ(pl::to_pixel(0.49), 0);
  EXPECT_EQ(pl::to_pixel(0.5), 1);
  EXPECT_EQ(pl::to_pixel(1.5), 2);
  EXPECT_EQ(pl::to_pixel(2.5), 3);  // not banker's rounding
  EXPECT_EQ(pl::to_pixel(127.49999), 127);
  EXPECT_EQ(pl::to_pixel(127.5), 128);
  EXPECT_EQ(pl::to_pixel(254.5), 255);
  EXPECT_EQ(pl::to_pixel(-0.4), 0);
  for (int v = 0; v <= 255; ++v) EXPECT_EQ(pl::to_pixel(v), v);
}

TEST(ToPixel, Saturates) {
  EXPECT_EQ(pl::to_pixel(255.4), 255);
  EXPECT_EQ(pl::to_pixel(255.5), 255);
  EXPECT_EQ(pl::to_pixel(256), 255);
  EXPECT_EQ(pl::to_pixel(1e300), 255);
  EXPECT_EQ(pl::to_pixel(std::numeric_limits<double>::infinity()), 255);
  EXPECT_EQ(pl::to_pixel(-0.5), 0);
  EXPECT_EQ(pl::to_pixel(-1), 0);
  EXPECT_EQ(pl::to_pixel(-1e300), 0);
  EXPECT_EQ(pl::to_pixel(-std::numeric_limits<double>::infinity()), 0);
  EXPECT_EQ(pl::to_pixel(std::numeric_limits<double>::quiet_NaN()), 0);
}

TEST(ToPixel, OfExpressions) {
  // The value every lut entry gets: to_pixel(expr(a)).
  EXPECT_EQ(pl::to_pixel(eval_ab("a / 2", 1)), 1);
  EXPECT_EQ(pl::to_pixel(eval_ab("a / 2", 3)), 2);
  EXPECT_EQ(pl::to_pixel(eval_ab("255 - a", 300)), 0);
  EXPECT_EQ(pl::to_pixel(eval_ab("a * 2", 200)), 255);
  EXPECT_EQ(pl::to_pixel(eval_ab("0 / 0")), 0);
  EXPECT_EQ(pl::to_pixel(eval_ab("1 / 0")), 255);
}
