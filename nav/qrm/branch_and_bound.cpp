#include "nav/qrm/branch_and_bound.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace neopipe::nav::qrm {
namespace {

using Live = std::uint64_t;  // bit j: constraint j may still be >= 0 somewhere in the box
constexpr std::size_t kMaxConstraints = 64;

struct Pending {
  Box box;
  int depth;
  Live live;
};

}  // namespace

Feasibility find_feasible(std::span<const Quadratic> constraints, const Box& box, int max_depth) {
  if (constraints.size() > kMaxConstraints)
    throw std::invalid_argument("branch and bound takes at most 64 constraints");
  std::vector<Quadratic> negations;
  negations.reserve(constraints.size());
  for (const Quadratic& g : constraints) negations.push_back(g.negated());
  std::vector<const Quadratic*> g(constraints.size());
  std::vector<const Quadratic*> minus(constraints.size());
  for (std::size_t j = 0; j < constraints.size(); ++j) {
    g[j] = &constraints[j];
    minus[j] = &negations[j];
  }
  return find_feasible(g, minus, box, max_depth);
}

Feasibility find_feasible(std::span<const Quadratic* const> constraints, std::span<const Quadratic* const> negated,
                          const Box& box, int max_depth) {
  Feasibility result;
  if (constraints.empty()) throw std::invalid_argument("branch and bound needs at least one constraint");
  if (constraints.size() > kMaxConstraints)
    throw std::invalid_argument("branch and bound takes at most 64 constraints");
  if (negated.size() != constraints.size())
    throw std::invalid_argument("branch and bound: one negation per constraint");
  const int n = constraints.front()->unknowns();
  for (const Quadratic* g : constraints) {
    if (g->unknowns() != n) throw std::invalid_argument("branch and bound: constraints differ in their unknowns");
  }
  // A constraint negative over a whole box is negative over its sub-boxes and at their centres: it can
  // neither discard them nor refuse a witness there, so they skip it. Neither this nor the order the
  // constraints are tried in (the one that discarded the last box first: it is likely to discard its
  // neighbour too) changes the result of spec §5's search, only its time.
  const std::size_t m = constraints.size();
  std::array<int, kMaxConstraints> order{};
  for (std::size_t j = 0; j < m; ++j) order[j] = static_cast<int>(j);
  const Live all = m == 64 ? ~Live{0} : (Live{1} << m) - 1;

  // Depth first, so the stack never holds more than one sibling per level. After a split the lower
  // half is visited next, in place: the same order as pushing both halves, without copying it.
  std::vector<Pending> stack;
  stack.reserve(static_cast<std::size_t>(max_depth) + 2);
  Pending at{box, 0, all};
  for (;;) {
    ++result.boxes;
    bool discarded = false;
    for (std::size_t k = 0; k < m; ++k) {
      const int j = order[k];
      if (((at.live >> j) & 1U) == 0) continue;
      if (constraints[j]->lower_bound(at.box) >= 0) {
        std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k),
                    order.begin() + static_cast<std::ptrdiff_t>(k) + 1);
        discarded = true;
        break;
      }
      if (negated[j]->lower_bound(at.box) > 0) at.live &= ~(Live{1} << j);
    }
    if (!discarded) {
      Point4 centre{};
      for (int i = 0; i < n; ++i) centre[i] = 0.5 * (at.box.lo[i] + at.box.hi[i]);
      bool inside = true;
      for (std::size_t j = 0; j < m && inside; ++j) {
        inside = ((at.live >> j) & 1U) == 0 || (*constraints[j])(centre) < 0;
      }
      if (inside) {
        result.witness = centre;
        return result;
      }
      if (at.depth < max_depth) {
        int axis = 0;
        for (int i = 1; i < n; ++i) {
          if (at.box.hi[i] - at.box.lo[i] > at.box.hi[axis] - at.box.lo[axis]) axis = i;
        }
        ++at.depth;
        stack.push_back(at);
        stack.back().box.lo[axis] = centre[axis];
        at.box.hi[axis] = centre[axis];
        continue;
      }
    }
    if (stack.empty()) break;
    at = stack.back();
    stack.pop_back();
  }
  return result;
}

}  // namespace neopipe::nav::qrm
