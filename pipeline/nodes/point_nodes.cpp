// Point nodes: each output pixel depends only on the input pixels at the same place.

#include <algorithm>
#include <cstdint>

#include "kernels/alu.hpp"
#include "kernels/convert.hpp"
#include "kernels/gray.hpp"
#include "kernels/histogram.hpp"
#include "kernels/lut.hpp"
#include "kernels/lut2.hpp"
#include "kernels/threshold.hpp"
#include "pipeline/expr.hpp"
#include "pipeline/nodes/nodes.hpp"

namespace neopipe::pipeline::nodes {
namespace {

using kernels::Footprint;

class GrayNode final : public Node {
 public:
  GrayNode() : Node({{"in", PortType::bgr8}}, {{"out", PortType::gray8}}, Footprint::point, FrameOrder::any) {}
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    kernels::bgr_to_gray_row(in.row(0, y), out, width);
  }
  bool fusable() const override { return true; }
};

class LutNode final : public Node {
 public:
  explicit LutNode(const kernels::Lut& table)
      : Node({{"in", PortType::gray8}}, {{"out", PortType::gray8}}, Footprint::point, FrameOrder::any), table_(table) {}
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    kernels::lut_row(in.row(0, y), out, width, table_);
  }
  bool fusable() const override { return true; }

 private:
  kernels::Lut table_;
};

// A fixed threshold, or Otsu's, chosen afresh for every frame from its histogram.
class ThresholdNode final : public Node {
 public:
  ThresholdNode(int fixed, bool otsu, std::uint8_t high)
      // Otsu's T is per-frame state kept in the node, so frames must come one at a time.
      : Node({{"in", PortType::gray8}}, {{"out", PortType::gray8}}, Footprint::point,
             otsu ? FrameOrder::in_order : FrameOrder::any),
        t_(fixed),
        otsu_(otsu),
        high_(high) {}
  void begin_frame(NodeIO& io) override {
    Node::begin_frame(io);
    if (otsu_) t_ = kernels::otsu_threshold(kernels::histogram(io.image(0)));
  }
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    if (t_ < 0) {
      std::fill_n(out, width, high_);
    } else {
      kernels::threshold_row(in.row(0, y), out, width, static_cast<std::uint8_t>(t_), high_);
    }
  }
  bool fusable() const override { return !otsu_; }

 private:
  int t_;
  bool otsu_;
  std::uint8_t high_;
};

class AluNode final : public Node {
 public:
  explicit AluNode(kernels::AluOp op)
      : Node({{"a", PortType::gray8}, {"b", PortType::gray8}}, {{"out", PortType::gray8}}, Footprint::point,
             FrameOrder::any),
        op_(op) {}
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    kernels::alu_row(op_, in.row(0, y), in.row(1, y), out, width);
  }
  bool fusable() const override { return true; }

 private:
  kernels::AluOp op_;
};

class Lut2Node final : public Node {
 public:
  explicit Lut2Node(kernels::Lut2 table)
      : Node({{"a", PortType::gray8}, {"b", PortType::gray8}}, {{"out", PortType::gray8}}, Footprint::point,
             FrameOrder::any),
        table_(std::move(table)) {}
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    kernels::lut2_row(in.row(0, y), in.row(1, y), out, width, table_);
  }
  bool fusable() const override { return true; }

 private:
  kernels::Lut2 table_;
};

class ConvertNode final : public Node {
 public:
  explicit ConvertNode(kernels::ConvertS16 c)
      : Node({{"in", PortType::s16}}, {{"out", PortType::gray8}}, Footprint::point, FrameOrder::any), c_(c) {}
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    kernels::convert_s16_row(in.row_as<std::int16_t>(0, y), out, width, c_);
  }
  bool fusable() const override { return true; }

 private:
  kernels::ConvertS16 c_;
};

Expr parse_expr(ParamReader& p, const std::vector<std::string>& vars) {
  const std::string text = *p.get_optional_string("expr");
  try {
    return Expr::parse(text, vars);
  } catch (const ExprError& e) {
    p.fail("expr", std::string(e.what()) + " at character " + std::to_string(e.column()) + " of \"" + text + "\"");
  }
}

kernels::Lut lut_from_params(ParamReader& p) {
  const bool has_table = p.has("table");
  const bool has_expr = p.has("expr");
  if (has_table == has_expr) p.fail("expr", "give exactly one of 'table' (256 values) or 'expr' (in terms of a)");
  kernels::Lut t{};
  if (has_table) {
    const auto v = p.get_int_list("table", 256, 0, 255);
    for (size_t i = 0; i < 256; ++i) t[i] = static_cast<std::uint8_t>(v[i]);
    return t;
  }
  const Expr e = parse_expr(p, {"a"});
  for (int a = 0; a < 256; ++a) {
    const double x = a;
    t[static_cast<size_t>(a)] = static_cast<std::uint8_t>(to_pixel(e.eval({&x, 1})));
  }
  return t;
}

}  // namespace

void register_point_nodes(KernelRegistry& r) {
  r.add({"gray", "BT.601 luma of a bgr8 image, bit-exact with cv::cvtColor(BGR2GRAY)",
         [](NodeContext&) { return std::make_unique<GrayNode>(); }});
  r.add({"lut", "point look-up table; params: table (256 values) or expr (in a, e.g. \"255 - a\")",
         [](NodeContext& c) { return std::make_unique<LutNode>(lut_from_params(c.params)); }});
  r.add({"threshold", "out = in > value ? high : 0; params: value (-1..255 or otsu, default otsu), high (255)",
         [](NodeContext& c) {
           const std::string v = c.params.get_string("value", "otsu");
           const bool otsu = v == "otsu";
           const int fixed = otsu ? 0 : c.params.get_int("value", 0, -1, 255);
           const int high = c.params.get_int("high", 255, 1, 255);
           return std::make_unique<ThresholdNode>(fixed, otsu, static_cast<std::uint8_t>(high));
         }});
  for (const char* op : {"add", "sub", "absdiff", "min", "max", "and", "or", "xor"}) {
    r.add({op, std::string("two-input ") + op + " of a and b (add and sub saturate)",
           [op](NodeContext&) { return std::make_unique<AluNode>(*kernels::alu_op_from_string(op)); }});
  }
  r.add({"lut2", "two-input table out = f(a, b); params: expr (in a and b, e.g. \"(a + 7*b + 4) / 8\")",
         [](NodeContext& c) {
           if (!c.params.has("expr")) c.params.fail("expr", "required: f(a, b), e.g. \"(a + 7*b + 4) / 8\"");
           const Expr e = parse_expr(c.params, {"a", "b"});
           return std::make_unique<Lut2Node>(kernels::Lut2::from_function([&](int a, int b) {
             const std::array<double, 2> v{static_cast<double>(a), static_cast<double>(b)};
             return static_cast<std::uint8_t>(to_pixel(e.eval(v)));
           }));
         }});
  r.add({"convert", "s16 to gray8: saturate(round(|v| / 2^shift)); params: abs (true), shift (0..15)",
         [](NodeContext& c) {
           kernels::ConvertS16 k;
           k.absolute = c.params.get_bool("abs", true);
           k.shift = c.params.get_int("shift", 0, 0, 15);
           return std::make_unique<ConvertNode>(k);
         }});
}

}  // namespace neopipe::pipeline::nodes
