#pragma once
// NX's topological map with its local metric (qualnav.md §9): places described by their ranges and
// edge headings (compass), each edge slot unexplored, explored (to which place and slot, its length
// and compass Δθ), open (runs out of reach) or blocked (too close to a marble). Routes are shortest
// by edge length over explored edges.

#include <Eigen/Core>
#include <cstddef>
#include <set>
#include <utility>
#include <vector>

#include "nav/nx/controls.hpp"

namespace neopipe::nav::nx {

enum class SlotState { unexplored, explored, open, blocked };

struct Slot {
  double heading_deg = 0;
  SlotState state = SlotState::unexplored;
  std::size_t to_place = 0;  ///< explored: the place at its far end
  int to_slot = 0;           ///< and the slot it arrives by there
  double length = 0;         ///< explored: mm
  double dtheta_deg = 0;     ///< explored: net change of the direction of travel
};

struct LearnedPlace {
  PlaceView view;
  std::vector<Slot> slots;
  /// Where NX's dead reckoning put it when it was found (compass frame, mm from where the
  /// exploration's odometry began): only ever compared with NX's own odometry.
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
};

/// One step of a route: leave `place` by `slot`.
struct Leg {
  std::size_t place = 0;
  int slot = 0;
};

class LearnedMap {
 public:
  std::size_t add_place(const PlaceView& view, const Eigen::Vector2d& position = Eigen::Vector2d::Zero());
  /// Joins slot `ps` of place p and slot `qs` of place q by an edge travelled from p.
  void link(std::size_t p, int ps, std::size_t q, int qs, double length, double dtheta_deg);
  void mark(std::size_t p, int slot, SlotState state);

  /// Whether `view` could be place p: ranges within `tolerance` (fraction) and as many slots, each
  /// agreeing with one of p's within `heading_tolerance_deg`.
  /// With `slots_to_agree` > 0, that many slots agreeing suffice (the expected end of a known edge,
  /// where a fourth marble nearly as near may turn one edge).
  [[nodiscard]] bool could_be(std::size_t p, const PlaceView& view, double tolerance, double heading_tolerance_deg,
                              std::size_t slots_to_agree = 0) const;
  /// Whether `view` could be place p by its range alone (within `tolerance`, a fraction).
  [[nodiscard]] bool range_fits(std::size_t p, const PlaceView& view, double tolerance) const;
  /// The places within `radius_mm` of `position` whose range agrees with `view`'s within `tolerance`,
  /// nearest first.
  [[nodiscard]] std::vector<std::size_t> near(const Eigen::Vector2d& position, double radius_mm, const PlaceView& view,
                                              double tolerance) const;
  /// Every place `view` could be, best range agreement first.
  [[nodiscard]] std::vector<std::size_t> candidates(const PlaceView& view, double tolerance,
                                                    double heading_tolerance_deg) const;
  /// The legs from `from` to `to` over explored edges, shortest by length; empty when none (or
  /// from == to).
  /// `avoid`: legs not to use (edges that failed).
  [[nodiscard]] std::vector<Leg> route(std::size_t from, std::size_t to,
                                       const std::set<std::pair<std::size_t, int>>& avoid = {}) const;
  /// Path length of the shortest route from `from` to every place (infinity: unreachable).
  [[nodiscard]] std::vector<double> distances(std::size_t from,
                                              const std::set<std::pair<std::size_t, int>>& avoid = {}) const;

  [[nodiscard]] std::size_t size() const { return places_.size(); }
  [[nodiscard]] const LearnedPlace& place(std::size_t i) const { return places_.at(i); }
  /// Explored edges, each counted once.
  [[nodiscard]] std::size_t edges() const;

 private:
  std::vector<LearnedPlace> places_;
};

}  // namespace neopipe::nav::nx
