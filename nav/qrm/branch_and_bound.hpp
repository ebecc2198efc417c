#pragma once
// Feasibility of a conjunction of strict quadratic inequalities g_j(x) < 0 over a box, by depth-first
// branch and bound (spec qrm.md §5).

#include <cstdint>
#include <optional>
#include <span>

#include "nav/qrm/quadratic.hpp"

namespace neopipe::nav::qrm {

struct Feasibility {
  /// A point of the box where every g_j < 0; none means infeasible in the paper's sense: any
  /// solution lies in boxes smaller than the depth allows.
  std::optional<Point4> witness;
  std::int64_t boxes = 0;  ///< boxes visited
};

/// Depth-first over boxes: a box is discarded when some g_j's lower bound over it is >= 0; otherwise
/// its centre is the witness if every g_j(centre) < 0; otherwise, below depth `max_depth`, its longest
/// edge (lowest index on ties) is halved and the lower half visited first. All constraints must have
/// the same number of unknowns; deterministic.
Feasibility find_feasible(std::span<const Quadratic> constraints, const Box& box, int max_depth);

/// The same search over constraints given by address with their negations (-g_j, which the search
/// uses to stop testing a constraint negative over a whole box): a caller testing many sets drawn
/// from the same quadratics (the 20 states of a measurement) builds each quadratic once.
Feasibility find_feasible(std::span<const Quadratic* const> constraints, std::span<const Quadratic* const> negated,
                          const Box& box, int max_depth);

}  // namespace neopipe::nav::qrm
