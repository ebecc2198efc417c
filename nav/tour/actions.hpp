#pragma once
// TOUR's sensorimotor world (qualnav.md §8, seed 002 "The Tour Model"): views are opaque ids that
// can only be matched; actions are turns and travels with optional magnitudes.

#include <cstdint>
#include <optional>
#include <variant>

namespace neopipe::nav::tour {

/// A view: the traveller's sensory input at an instant, opaque (only equality means anything).
using ViewId = std::uint64_t;

/// (Turn α): α degrees counter-clockwise (so a right turn is negative).
struct Turn {
  double alpha_deg = 0;
};

/// (Travel δ Δθ): δ the distance travelled; Δθ the net change of heading during the travel, degrees,
/// when it is known (absent: anything in [−180°, 180°]).
struct Travel {
  double distance = 0;
  std::optional<double> dtheta_deg;
};

using Action = std::variant<Turn, Travel>;

/// The qualitative magnitude of a turn (seed 002, "Regions, Boundaries, and Containment").
enum class TurnKind { none, right, left, around };

/// Right: α in (−180°, 0); Left: (0, 180°); Around: ±180°; none: 0. Decision: α is wrapped to
/// (−180°, 180°] first, and within `tolerance_deg` of 0 or of ±180° counts as none or around (0 by
/// default: the exact reading of the spec).
TurnKind turn_kind(double alpha_deg, double tolerance_deg = 0);

/// α wrapped to (−180°, 180°].
double wrap_turn_deg(double alpha_deg);

bool same_action(const Action& a, const Action& b);

}  // namespace neopipe::nav::tour
