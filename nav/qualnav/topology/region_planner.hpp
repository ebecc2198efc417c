#pragma once
// The orientation-region planner (spec qualnav.md §7; seed 002 Fig. 13) over remembered viewframes,
// and its shortcut. Its input is its own: a sequence of observations (the sign of each pair a
// viewframe sees, the compass bearing of each landmark it sees, and optionally the compass heading
// of the move that crossed into it), so that it needs nothing from the metric level.
//
// Nodes are the distinct sign vectors, in order of first appearance; consecutive observations with
// different vectors give the edges. The plan: one path leaves the start through each neighbour and
// one the goal through each of its neighbours; each step a path moves to the unvisited neighbour
// whose heading is closest to the heading of its own first step (ties: lower id); after each step,
// if its tip or a neighbour of the tip lies on a path from the other end, the two are joined.
// No meeting: breadth-first search (Decision).

#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "nav/qualnav/topology/lpb.hpp"
#include "nav/qualnav/topology/productions.hpp"

namespace neopipe::nav::qualnav {

/// The sign of each pair a viewframe sees; pairs are keyed with first < second.
using PairSigns = std::map<LandmarkPair, int>;

/// A sign vector over `pairs` as PairSigns: each pair keyed first < second, its sign flipped when
/// the pair was given the other way round. Sizes that differ are std::invalid_argument.
PairSigns to_pair_signs(std::span<const LandmarkPair> pairs, const SignVector& signs);

/// One remembered viewframe, as the planner needs it.
struct RegionObservation {
  PairSigns signs;
  std::vector<Sighting> bearings;          ///< compass bearings (counter-clockwise, radians)
  std::optional<double> crossing_heading;  ///< compass heading of the move that crossed into it
};

/// The observation of a panorama: the signs of every pair of the landmarks in view (pairs keyed
/// first < second), from compass bearings.
RegionObservation observe_regions(std::span<const Sighting> seen, std::optional<double> crossing_heading = {});

struct RegionEdge {
  std::size_t to = 0;
  std::optional<double> heading;  ///< compass heading to leave by (radians), when known
};

struct RegionNode {
  PairSigns signs;
  std::vector<Sighting> bearings;  ///< of the first viewframe with these signs
  std::vector<RegionEdge> edges;   ///< sorted by `to`, one per neighbour
};

/// The planner's graph: a node per distinct sign vector of the remembered viewframes.
class RegionGraph {
 public:
  /// Observations in the order they were made (one viewpath, or several one after the other with
  /// `breaks` marking the index where each new viewpath starts: no edge crosses a break).
  explicit RegionGraph(std::span<const RegionObservation> observations, std::span<const std::size_t> breaks = {});

  [[nodiscard]] std::span<const RegionNode> nodes() const { return nodes_; }
  /// The node of each observation, in order.
  [[nodiscard]] std::span<const std::size_t> node_of_observation() const { return node_of_; }
  [[nodiscard]] std::optional<std::size_t> node_with(const PairSigns& signs) const;
  /// The heading of the edge from -> to, or std::nullopt if there is none or it is unknown.
  [[nodiscard]] std::optional<double> heading(std::size_t from, std::size_t to) const;
  [[nodiscard]] bool adjacent(std::size_t from, std::size_t to) const;

 private:
  void link(std::size_t from, std::size_t to, std::optional<double> heading);

  std::vector<RegionNode> nodes_;
  std::vector<std::size_t> node_of_;
  std::map<PairSigns, std::size_t> index_;
};

/// The heading of an edge (Decision of §7): the compass heading of the recorded crossing, or else
/// the bisector of the bearings of the first pair whose sign differs between the two nodes (as seen
/// from `from`); std::nullopt when neither is known.
std::optional<double> edge_heading(const RegionNode& from, const RegionNode& to,
                                   std::optional<double> crossing_heading);

struct RegionPlan {
  std::vector<std::size_t> nodes;               ///< start first, goal last
  std::vector<std::optional<double>> headings;  ///< one per step (nodes.size() − 1)
  bool breadth_first = false;                   ///< the paths never met: breadth-first search
};

/// The plan from `start` to `goal`, or std::nullopt when the goal cannot be reached. Node ids out of
/// range are std::out_of_range.
std::optional<RegionPlan> plan_regions(const RegionGraph& graph, std::size_t start, std::size_t goal);

/// Whether the robot can head straight to a later planned region (the paper's shortcut).
struct RegionShortcut {
  bool possible = false;
  std::vector<LandmarkPair> separating;        ///< pairs whose sign differs from the target's
  std::vector<HeadingSpecifier> specifiers;    ///< one per separating pair, over the view
  std::optional<HeadingSpecifier> production;  ///< their production, when not "–"
  std::string reason;                          ///< why not, when not possible
};

/// The shortcut test from the current view (compass bearings, optional ranges by id) to `target`:
/// every LPB of the target must be visible; the separating ones become specifiers by §4's crossing
/// rule (b when the pair is more than 90° apart, else l or r beyond the nearer landmark when ranges
/// tell it, else b); the production over the view's left-to-right order must not be "–". A view
/// already in the target's region is possible with no separating pairs.
RegionShortcut shortcut_to(const RegionNode& target, std::span<const Sighting> view,
                           const std::map<LandmarkId, double>& ranges = {});

/// The position in plan.nodes of the furthest node after position `at` that the shortcut can reach
/// from `view`, or std::nullopt.
std::optional<std::size_t> furthest_shortcut(const RegionGraph& graph, const RegionPlan& plan, std::size_t at,
                                             std::span<const Sighting> view,
                                             const std::map<LandmarkId, double>& ranges = {});

}  // namespace neopipe::nav::qualnav
