#include "nav/qrm/branch_and_bound.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace neopipe::nav::qrm {
namespace {

using Live = std::uint64_t;  // bit j: constraint j may still be >= 0 somewhere in the box

struct Pending {
  Box box;
  int depth;
  Live live;
};

}  // namespace

Feasibility find_feasible(std::span<const Quadratic> constraints, const Box& box, int max_depth) {
  Feasibility result;
  if (constraints.empty()) throw std::invalid_argument("branch and bound needs at least one constraint");
  if (constraints.size() > 64) throw std::invalid_argument("branch and bound takes at most 64 constraints");
  const int n = constraints.front().unknowns();
  for (const Quadratic& g : constraints) {
    if (g.unknowns() != n) throw std::invalid_argument("branch and bound: constraints differ in their unknowns");
  }
  // A constraint negative over a whole box is negative over its sub-boxes and at their centres: it can
  // neither discard them nor refuse a witness there, so they skip it. Neither this nor the order the
  // constraints are tried in (the one that discarded the last box first: it is likely to discard its
  // neighbour too) changes the result of spec §5's search, only its time.
  std::vector<Quadratic> negated;
  negated.reserve(constraints.size());
  for (const Quadratic& g : constraints) negated.push_back(g.negated());
  std::vector<int> order(constraints.size());
  for (std::size_t j = 0; j < order.size(); ++j) order[j] = static_cast<int>(j);
  const Live all = constraints.size() == 64 ? ~Live{0} : (Live{1} << constraints.size()) - 1;

  // Depth first, so the stack never holds more than one sibling per level.
  std::vector<Pending> stack;
  stack.reserve(static_cast<std::size_t>(max_depth) + 2);
  stack.push_back({box, 0, all});
  while (!stack.empty()) {
    Pending at = stack.back();
    stack.pop_back();
    ++result.boxes;
    bool discarded = false;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const int j = order[k];
      if (((at.live >> j) & 1U) == 0) continue;
      if (constraints[j].lower_bound(at.box) >= 0) {
        std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k),
                    order.begin() + static_cast<std::ptrdiff_t>(k) + 1);
        discarded = true;
        break;
      }
      if (negated[j].lower_bound(at.box) > 0) at.live &= ~(Live{1} << j);
    }
    if (discarded) continue;
    Point4 centre{};
    for (int i = 0; i < n; ++i) centre[i] = 0.5 * (at.box.lo[i] + at.box.hi[i]);
    bool inside = true;
    for (std::size_t j = 0; j < constraints.size() && inside; ++j) {
      inside = ((at.live >> j) & 1U) == 0 || constraints[j](centre) < 0;
    }
    if (inside) {
      result.witness = centre;
      return result;
    }
    if (at.depth >= max_depth) continue;
    int axis = 0;
    for (int i = 1; i < n; ++i) {
      if (at.box.hi[i] - at.box.lo[i] > at.box.hi[axis] - at.box.lo[axis]) axis = i;
    }
    Pending lower{at.box, at.depth + 1, at.live};
    Pending upper{at.box, at.depth + 1, at.live};
    lower.box.hi[axis] = centre[axis];
    upper.box.lo[axis] = centre[axis];
    stack.push_back(upper);
    stack.push_back(lower);
  }
  return result;
}

}  // namespace neopipe::nav::qrm
