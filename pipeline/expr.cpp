#include "pipeline/expr.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <functional>

namespace neopipe::pipeline {

struct Expr::Node {
  std::function<double(std::span<const double>)> eval;
};

namespace {

using NodePtr = std::shared_ptr<const Expr::Node>;

NodePtr make(std::function<double(std::span<const double>)> f) {
  return std::make_shared<const Expr::Node>(Expr::Node{std::move(f)});
}

class Parser {
 public:
  Parser(std::string_view text, const std::vector<std::string>& vars) : s_(text), vars_(vars) {}

  NodePtr parse() {
    NodePtr e = ternary();
    skip();
    if (pos_ < s_.size()) fail("unexpected '" + std::string(1, s_[pos_]) + "'");
    return e;
  }

 private:
  [[noreturn]] void fail(const std::string& msg) const { throw ExprError(msg, pos_ + 1); }

  void skip() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_])) != 0) ++pos_;
  }

  bool eat(std::string_view tok) {
    skip();
    if (s_.substr(pos_, tok.size()) == tok) {
      pos_ += tok.size();
      return true;
    }
    return false;
  }

  NodePtr ternary() {
    NodePtr c = logic_or();
    if (!eat("?")) return c;
    NodePtr a = ternary();
    if (!eat(":")) fail("expected ':' in c ? x : y");
    NodePtr b = ternary();
    return make([c, a, b](auto v) { return c->eval(v) != 0 ? a->eval(v) : b->eval(v); });
  }

  NodePtr logic_or() {
    NodePtr l = logic_and();
    while (eat("||")) {
      NodePtr r = logic_and();
      l = make([l, r](auto v) { return (l->eval(v) != 0 || r->eval(v) != 0) ? 1.0 : 0.0; });
    }
    return l;
  }

  NodePtr logic_and() {
    NodePtr l = comparison();
    while (eat("&&")) {
      NodePtr r = comparison();
      l = make([l, r](auto v) { return (l->eval(v) != 0 && r->eval(v) != 0) ? 1.0 : 0.0; });
    }
    return l;
  }

  NodePtr comparison() {
    NodePtr l = additive();
    for (;;) {
      std::function<bool(double, double)> op;
      if (eat("<=")) {
        op = std::less_equal<>();
      } else if (eat(">=")) {
        op = std::greater_equal<>();
      } else if (eat("==")) {
        op = std::equal_to<>();
      } else if (eat("!=")) {
        op = std::not_equal_to<>();
      } else if (eat("<")) {
        op = std::less<>();
      } else if (eat(">")) {
        op = std::greater<>();
      } else {
        return l;
      }
      NodePtr r = additive();
      l = make([l, r, op](auto v) { return op(l->eval(v), r->eval(v)) ? 1.0 : 0.0; });
    }
  }

  NodePtr additive() {
    NodePtr l = multiplicative();
    for (;;) {
      if (eat("+")) {
        NodePtr r = multiplicative();
        l = make([l, r](auto v) { return l->eval(v) + r->eval(v); });
      } else if (eat("-")) {
        NodePtr r = multiplicative();
        l = make([l, r](auto v) { return l->eval(v) - r->eval(v); });
      } else {
        return l;
      }
    }
  }

  NodePtr multiplicative() {
    NodePtr l = unary();
    for (;;) {
      if (eat("*")) {
        NodePtr r = unary();
        l = make([l, r](auto v) { return l->eval(v) * r->eval(v); });
      } else if (eat("/")) {
        NodePtr r = unary();
        l = make([l, r](auto v) { return l->eval(v) / r->eval(v); });
      } else if (eat("%")) {
        NodePtr r = unary();
        l = make([l, r](auto v) { return std::fmod(l->eval(v), r->eval(v)); });
      } else {
        return l;
      }
    }
  }

  NodePtr unary() {
    if (eat("-")) {
      NodePtr e = unary();
      return make([e](auto v) { return -e->eval(v); });
    }
    if (eat("+")) return unary();
    if (eat("!")) {
      NodePtr e = unary();
      return make([e](auto v) { return e->eval(v) == 0 ? 1.0 : 0.0; });
    }
    return power();
  }

  NodePtr power() {
    NodePtr base = primary();
    if (!eat("^")) return base;
    NodePtr exponent = unary();  // right-associative: a^b^c = a^(b^c)
    return make([base, exponent](auto v) { return std::pow(base->eval(v), exponent->eval(v)); });
  }

  NodePtr primary() {
    skip();
    if (pos_ >= s_.size()) fail("unexpected end of expression");
    if (eat("(")) {
      NodePtr e = ternary();
      if (!eat(")")) fail("expected ')'");
      return e;
    }
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '.') {
      // Decimal only (from_chars, unlike strtod, takes no hex, "inf" or locale).
      double value = 0;
      const char* first = s_.data() + pos_;
      const auto [end, ec] = std::from_chars(first, s_.data() + s_.size(), value, std::chars_format::general);
      if (ec != std::errc() || end == first) fail("bad number");
      const size_t start = pos_;
      pos_ += static_cast<size_t>(end - first);
      if (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) != 0 || s_[pos_] == '_')) {
        pos_ = start;
        fail("bad number");
      }
      return make([value](auto) { return value; });
    }
    if (std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_') {
      const size_t start = pos_;
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) != 0 || s_[pos_] == '_')) ++pos_;
      const std::string name(s_.substr(start, pos_ - start));
      const auto var = std::find(vars_.begin(), vars_.end(), name);
      if (var != vars_.end()) {
        const auto i = static_cast<size_t>(var - vars_.begin());
        return make([i](auto v) { return v[i]; });
      }
      if (!eat("(")) {
        pos_ = start;
        std::string known;
        for (const auto& v : vars_) known += (known.empty() ? "" : ", ") + v;
        fail("unknown name '" + name + "' (variables: " + known + ")");
      }
      return call(name, start);
    }
    fail("unexpected '" + std::string(1, c) + "'");
  }

  NodePtr call(const std::string& name, size_t start) {
    std::vector<NodePtr> args;
    if (!eat(")")) {
      do {
        args.push_back(ternary());
      } while (eat(","));
      if (!eat(")")) fail("expected ')' after the arguments of " + name);
    }
    const auto arity = [&](size_t n) {
      if (args.size() != n) {
        pos_ = start;
        fail(name + "() takes " + std::to_string(n) + " argument" + (n == 1 ? "" : "s"));
      }
    };
    const auto unary_fn = [&](double (*f)(double)) {
      arity(1);
      NodePtr a = args[0];
      return make([a, f](auto v) { return f(a->eval(v)); });
    };
    if (name == "abs") return unary_fn([](double x) { return std::fabs(x); });
    if (name == "floor") return unary_fn([](double x) { return std::floor(x); });
    if (name == "ceil") return unary_fn([](double x) { return std::ceil(x); });
    if (name == "round") return unary_fn([](double x) { return std::round(x); });
    if (name == "sqrt") return unary_fn([](double x) { return std::sqrt(x); });
    if (name == "exp") return unary_fn([](double x) { return std::exp(x); });
    if (name == "log") return unary_fn([](double x) { return std::log(x); });
    if (name == "min" || name == "max" || name == "pow") {
      arity(2);
      NodePtr a = args[0];
      NodePtr b = args[1];
      if (name == "min") return make([a, b](auto v) { return std::min(a->eval(v), b->eval(v)); });
      if (name == "max") return make([a, b](auto v) { return std::max(a->eval(v), b->eval(v)); });
      return make([a, b](auto v) { return std::pow(a->eval(v), b->eval(v)); });
    }
    if (name == "clamp") {
      arity(3);
      NodePtr x = args[0];
      NodePtr lo = args[1];
      NodePtr hi = args[2];
      return make([x, lo, hi](auto v) { return std::min(std::max(x->eval(v), lo->eval(v)), hi->eval(v)); });
    }
    pos_ = start;
    fail("unknown function '" + name + "'");
  }

  std::string_view s_;
  const std::vector<std::string>& vars_;
  size_t pos_ = 0;
};

}  // namespace

Expr Expr::parse(std::string_view text, const std::vector<std::string>& variables) {
  Expr e;
  e.root_ = Parser(text, variables).parse();
  return e;
}

double Expr::eval(std::span<const double> values) const {
  return root_->eval(values);
}

int to_pixel(double v) {
  if (std::isnan(v)) return 0;
  return static_cast<int>(std::clamp(std::round(v), 0.0, 255.0));
}

}  // namespace neopipe::pipeline
