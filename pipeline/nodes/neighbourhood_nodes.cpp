// 3x3 neighbourhood nodes: each output row reads the input rows above and below it.

#include <array>
#include <string>

#include "kernels/bool3x3.hpp"
#include "kernels/conv3x3.hpp"
#include "pipeline/expr.hpp"
#include "pipeline/nodes/neighbour_rows.hpp"
#include "pipeline/nodes/nodes.hpp"

namespace neopipe::pipeline::nodes {
namespace {

using kernels::Footprint;

class Conv3x3Node final : public Node {
 public:
  Conv3x3Node(kernels::Conv3x3 k, PortType out)
      : Node({{"in", PortType::gray8}}, {{"out", out}}, Footprint::neighbourhood3x3, FrameOrder::any),
        k_(k),
        s16_(out == PortType::s16),
        vertical_(k.border, static_cast<std::uint8_t>(k.border.value)) {}
  void configure(cv::Size frame_size) override { vertical_.configure(frame_size); }
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    const Neighbours r = vertical_.rows(in, 0, y);
    if (s16_) {
      kernels::conv3x3_row(r.up, r.mid, r.down, reinterpret_cast<std::int16_t*>(out),  // NOLINT
                           width, k_);
    } else {
      kernels::conv3x3_row(r.up, r.mid, r.down, out, width, k_);
    }
  }
  bool fusable() const override { return true; }

 private:
  kernels::Conv3x3 k_;
  bool s16_;
  VerticalBorder vertical_;
};

class Bool3x3Node final : public Node {
 public:
  explicit Bool3x3Node(kernels::Bool3x3 k)
      : Node({{"in", PortType::gray8}}, {{"out", PortType::gray8}}, Footprint::neighbourhood3x3, FrameOrder::any),
        k_(k),
        vertical_(k.border, k.border.value != 0 ? 255 : 0) {}
  void configure(cv::Size frame_size) override { vertical_.configure(frame_size); }
  void compute_row(const RowInputs& in, std::uint8_t* out, int y, int width) const override {
    const Neighbours r = vertical_.rows(in, 0, y);
    kernels::bool3x3_row(r.up, r.mid, r.down, out, width, k_);
  }
  bool fusable() const override { return true; }

 private:
  kernels::Bool3x3 k_;
  VerticalBorder vertical_;
};

kernels::Border border_params(ParamReader& p, int max_value) {
  kernels::Border b;
  b.mode = p.get_choice("border", "replicate", {"replicate", "constant"}) == "constant"
               ? kernels::BorderMode::constant
               : kernels::BorderMode::replicate;
  b.value = p.get_int("border_value", 0, 0, max_value);
  return b;
}

kernels::Conv3x3 conv_params(ParamReader& p) {
  const std::string preset =
      p.get_choice("preset", "identity", {"identity", "smooth", "sobel_x", "sobel_y", "laplace", "sharpen"});
  kernels::Conv3x3 k;
  if (preset == "smooth") k = kernels::smooth3x3();
  if (preset == "sobel_x") k = kernels::sobel_x3x3();
  if (preset == "sobel_y") k = kernels::sobel_y3x3();
  if (preset == "laplace") k.weights = {0, 1, 0, 1, -4, 1, 0, 1, 0};
  if (preset == "sharpen") k.weights = {0, -1, 0, -1, 5, -1, 0, -1, 0};
  if (p.has("weights")) {
    const auto w = p.get_int_list("weights", 9, -65535, 65535);
    std::copy(w.begin(), w.end(), k.weights.begin());
  }
  k.shift = p.get_int("shift", k.shift, 0, 16);
  k.border = border_params(p, 255);
  return k;
}

kernels::BoolTable bool_table_params(ParamReader& p) {
  const bool has_op = p.has("op");
  const bool has_pattern = p.has("pattern");
  const bool has_expr = p.has("expr");
  const bool has_table = p.has("table");
  if (int{has_op} + int{has_pattern} + int{has_expr} + int{has_table} != 1) {
    p.fail("op", "give exactly one of op (erode | dilate), pattern (hit-or-miss), expr or table (512 values)");
  }
  if (has_op) {
    return p.get_choice("op", "erode", {"erode", "dilate"}) == "erode" ? kernels::erode_table()
                                                                       : kernels::dilate_table();
  }
  if (has_pattern) {
    const std::string pattern = *p.get_optional_string("pattern");
    try {
      return kernels::hit_or_miss_table(pattern);
    } catch (const kernels::KernelError& e) {
      p.fail("pattern", e.what());
    }
  }
  if (has_table) {
    const auto v = p.get_int_list("table", 512, 0, 1);
    return kernels::BoolTable::from_function([&](unsigned i) { return v[i] != 0; });
  }
  // The nine neighbours, 0 or 1, by compass name in reading order (bit 0 is nw).
  const std::vector<std::string> vars{"nw", "n", "ne", "w", "c", "e", "sw", "s", "se"};
  const std::string text = *p.get_optional_string("expr");
  Expr e;
  try {
    e = Expr::parse(text, vars);
  } catch (const ExprError& err) {
    p.fail("expr", std::string(err.what()) + " at character " + std::to_string(err.column()) + " of \"" + text + "\"");
  }
  return kernels::BoolTable::from_function([&](unsigned i) {
    std::array<double, 9> v{};
    for (unsigned b = 0; b < 9; ++b) v[b] = (i >> b) & 1U;
    return e.eval(v) != 0;
  });
}

}  // namespace

void register_neighbourhood_nodes(KernelRegistry& r) {
  r.add({"conv3x3",
         "3x3 weighted sum, shifted and saturated; params: preset (identity | smooth | sobel_x | sobel_y | laplace | "
         "sharpen), weights (9), shift (0..16), output (gray8 | s16), border (replicate | constant), border_value",
         [](NodeContext& c) {
           const kernels::Conv3x3 k = conv_params(c.params);
           const PortType out =
               c.params.get_choice("output", "gray8", {"gray8", "s16"}) == "s16" ? PortType::s16 : PortType::gray8;
           return std::make_unique<Conv3x3Node>(k, out);
         }});
  r.add({"bool3x3",
         "3x3 Boolean neighbourhood through a 512-entry table; params: op (erode | dilate), pattern (hit-or-miss, "
         "e.g. \"x1x 111 x1x\"), expr (in nw n ne w c e sw s se) or table (512), high (255), border, border_value",
         [](NodeContext& c) {
           kernels::Bool3x3 k;
           k.table = bool_table_params(c.params);
           k.high = static_cast<std::uint8_t>(c.params.get_int("high", 255, 1, 255));
           k.border = border_params(c.params, 1);
           return std::make_unique<Bool3x3Node>(k);
         }});
}

}  // namespace neopipe::pipeline::nodes
