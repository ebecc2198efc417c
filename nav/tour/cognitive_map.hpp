#pragma once
// TOUR's topological and metric map (qualnav.md §8, seed 002 "The Topological Map", "The Metric
// Map"), built incrementally from a stream of <V, A, V'> schemas.
//
// Topology: a turn keeps the place; a travel changes place, keeps the path and the direction, and
// sets order(place V, place V', path) = direction(V); a path's first direction is +1. A turn around
// keeps the path and reverses the direction (the paper's "face the opposite direction along the
// same path"); turn 0 keeps both. When a schema joins two views that had different places or
// paths, they merge (the later into the earlier, positions and sides carried over).
// Boundary regions, after <V1, Travel, V2> <V2, Turn, V3> <V3, Travel, V4>, P1 = place(V1),
// P3 = place(V4): Right puts P3 in right(path1) if direction(V2, path1) = +1, else in left, and P1
// in right(path2) if direction(V3, path2) = +1, else in left; Left mirrors; Around adds nothing.
// Metric: local headings (the first view at a place 0, then + α), local positions on a path (+ δ ·
// direction), pathdistance; one orientation frame (the first view 0°) whose headings are intervals
// propagated by α and Δθ (an unknown Δθ is [−180°, 180°]), intersected when two constraints meet.
// The three distortion heuristics of the paper are switches (DistortionHeuristics).

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "nav/tour/actions.hpp"

namespace neopipe::nav::tour {

using PlaceId = std::uint32_t;
using PathId = std::uint32_t;

/// A closed interval of degrees or mm.
struct Interval {
  double lo = 0;
  double hi = 0;
  [[nodiscard]] bool contains(double x) const { return lo <= x && x <= hi; }
  [[nodiscard]] double width() const { return hi - lo; }
};

/// The paper's heuristics that predictably distort the map ("Distorted Cognitive Maps").
struct DistortionHeuristics {
  bool right_angles = false;              ///< (1) a turn near ±90° is exactly ±90°
  double right_angle_tolerance_deg = 15;  ///< what "near" means for (1)
  bool straight_travel = false;           ///< (2) every travel has Δθ = 0
  bool travel_is_distance = false;        ///< (3) distance(place(V1), place(V2)) = δ
};

struct TourSettings {
  DistortionHeuristics heuristics;
  double turn_tolerance_deg = 0;  ///< turn_kind's tolerance for none and around
};

class CognitiveMap {
 public:
  explicit CognitiveMap(const TourSettings& settings = {});

  /// Assimilates one <V, A, V'>.
  void assimilate(ViewId view, const Action& action, ViewId result);
  /// Place recognition from outside the stream (NX's place matching): `other` is seen from the same
  /// place as `view` after turning `alpha_deg`. Like a turn, without entering the schema history.
  void recognise(ViewId view, double alpha_deg, ViewId other);

  // The topological map.
  [[nodiscard]] std::optional<PlaceId> place(ViewId view) const;
  [[nodiscard]] std::optional<PathId> path(ViewId view) const;
  /// +1 or −1 along path(view); nullopt while the view has no path.
  [[nodiscard]] std::optional<int> direction(ViewId view) const;
  [[nodiscard]] std::vector<PlaceId> places() const;
  [[nodiscard]] std::vector<PathId> paths() const;
  /// The places on `path`, in its +1 order.
  [[nodiscard]] std::vector<PlaceId> places_on(PathId path) const;
  /// +1 if `a` comes before `b` along `path` (its +1 direction), −1 after; nullopt unless both lie on it.
  [[nodiscard]] std::optional<int> order(PlaceId a, PlaceId b, PathId path) const;
  [[nodiscard]] bool in_right(PlaceId place, PathId path) const;
  [[nodiscard]] bool in_left(PlaceId place, PathId path) const;
  /// The boundary heuristic: a path with `a` on one side and `b` on the other, if one is known.
  [[nodiscard]] std::optional<PathId> boundary_between(PlaceId a, PlaceId b) const;
  /// A route of places from `a` to `b` over the travels experienced, shortest by δ; when the
  /// boundary heuristic knows a path between them, the route goes through that path (A -> path -> B).
  /// Empty when none is known.
  [[nodiscard]] std::vector<PlaceId> route(PlaceId a, PlaceId b) const;

  // The metric map.
  [[nodiscard]] std::optional<double> local_heading(ViewId view) const;
  [[nodiscard]] std::optional<double> local_position(PlaceId place, PathId path) const;
  [[nodiscard]] std::optional<double> path_distance(PlaceId a, PlaceId b, PathId path) const;
  /// heading(V, OF) in the orientation frame, as an interval of degrees.
  [[nodiscard]] std::optional<Interval> heading(ViewId view) const;
  /// distance(place1, place2): only with heuristic (3), the δ of a travel between them.
  [[nodiscard]] std::optional<double> distance(PlaceId a, PlaceId b) const;
  /// Constraints on the orientation frame that contradicted what it held (kept the old interval).
  [[nodiscard]] int heading_conflicts() const { return heading_conflicts_; }

 private:
  struct ViewFacts {
    std::optional<PlaceId> place;
    std::optional<PathId> path;
    int direction = 0;
    std::optional<double> local_heading;
    std::optional<Interval> heading;
  };
  struct Link {
    PlaceId a = 0;
    PlaceId b = 0;
    double length = 0;
  };
  struct Remembered {
    ViewId view = 0;
    Action action;
    ViewId result = 0;
  };

  ViewFacts& facts(ViewId view);
  PlaceId place_of(ViewId view);
  void merge_places(PlaceId keep, PlaceId gone, double heading_offset);
  void merge_paths(PathId keep, PathId gone, bool flip, double offset);
  void assimilate_turn(ViewId view, double alpha, ViewId result);
  void assimilate_travel(ViewId view, const Travel& travel, ViewId result);
  void assimilate_boundaries();
  void constrain_heading(ViewId from, Interval change, ViewId to);
  [[nodiscard]] std::vector<PlaceId> shortest(PlaceId a, PlaceId b, double* length) const;

  TourSettings settings_;
  std::map<ViewId, ViewFacts> views_;
  std::set<PlaceId> places_;
  std::set<PathId> paths_;
  std::map<std::pair<PlaceId, PathId>, double> position_;
  std::map<PathId, std::set<PlaceId>> right_;
  std::map<PathId, std::set<PlaceId>> left_;
  std::vector<Link> links_;
  std::map<std::pair<PlaceId, PlaceId>, double> straight_;
  std::deque<Remembered> recent_;  ///< the last three schemas, for the Travel–Turn–Travel rule
  PlaceId next_place_ = 0;
  PathId next_path_ = 0;
  int heading_conflicts_ = 0;
};

}  // namespace neopipe::nav::tour
