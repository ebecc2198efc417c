#include "nav/nx/explorer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "nav/nx/arrival.hpp"

namespace neopipe::nav::nx {

tour::ViewId nx_view(std::size_t place, int slot, bool arrived) {
  return static_cast<tour::ViewId>(place) * 64 + static_cast<tour::ViewId>(slot) * 2 + (arrived ? 1 : 0);
}

namespace {

// Known edges that may fail to lead where the map says before the exploration gives up.
constexpr int kMaxDetours = 50;
// Times the known edges given up on are tried again when they cut the agenda off.
constexpr int kMaxForgiving = 3;

// The explorer's state across one run.
class Exploration {
 public:
  Exploration(Robot& robot, LearnedMap& map, const ExploreSettings& settings, tour::CognitiveMap* tour,
              ExploreObserver* observer)
      : robot_(robot), map_(map), settings_(settings), tour_(tour), observer_(observer) {}

  ExploreReport run() {
    if (climb_to_place(robot_).ending != ClimbEnding::place) return finish("no place");
    const std::optional<PlaceView> first = describe_place(robot_);
    if (!first || first->slots.empty()) return finish("no place");
    at_ = new_place(*first);
    facing_ = {nx_view(at_, 0, false), map_.place(at_).slots[0].heading_deg};
    while (true) {
      if (map_.size() >= settings_.max_places) return finish("place budget");
      if (robot_.moves() >= settings_.max_moves) return finish("move budget");
      std::optional<Leg> next = nearest_unexplored();
      if (!next && !failed_.empty() && forgiven_++ < kMaxForgiving) {
        // The edges given up on cut the rest of the agenda off: under noise they may have failed by
        // chance, so they get another chance (a few times at most).
        failed_.clear();
        failures_.clear();
        next = nearest_unexplored();
      }
      if (!next) return finish("agenda empty");
      bool on_route = true;
      for (const Leg& leg : map_.route(at_, next->place, failed_)) {
        if (!travel_known(leg)) {
          on_route = false;
          break;
        }
      }
      if (lost_) return finish("lost: no way back from an edge");
      if (!on_route) {
        // Re-localised (or back where the leg began): plan again, a few times at most.
        if (++detours_ > kMaxDetours) return finish("lost: known edges keep leading elsewhere");
        continue;
      }
      explore_slot(next->place, next->slot);
      if (lost_) return finish("lost: no way back from an edge");
    }
  }

 private:
  struct Facing {
    tour::ViewId view = 0;
    double heading = 0;
  };

  ExploreReport finish(const char* ending) {
    report_.ending = ending;
    report_.places = map_.size();
    report_.edges = map_.edges();
    report_.moves = robot_.moves();
    report_.frames = robot_.frames();
    report_.travelled_mm = robot_.travelled_mm();
    return report_;
  }

  std::size_t new_place(const PlaceView& view) {
    const std::size_t p = map_.add_place(view, robot_.odometry());
    robot_.set_odometry(robot_.odometry());
    if (observer_ != nullptr) observer_->place_found(p);
    return p;
  }

  // The unexplored (place, edge) pair nearest by the map, earliest place and slot on ties.
  std::optional<Leg> nearest_unexplored() const {
    const std::vector<double> d = map_.distances(at_, failed_);
    std::optional<Leg> best;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < map_.size(); ++p) {
      const auto& slots = map_.place(p).slots;
      for (std::size_t s = 0; s < slots.size(); ++s) {
        if (slots[s].state == SlotState::unexplored && d[p] < best_d) {
          best = Leg{p, static_cast<int>(s)};
          best_d = d[p];
        }
      }
    }
    return best;
  }

  void tell_tour_departure(std::size_t p, int slot) {
    const tour::ViewId v = nx_view(p, slot, false);
    const double heading = map_.place(p).slots.at(static_cast<std::size_t>(slot)).heading_deg;
    if (tour_ != nullptr && facing_.view != v)
      tour_->assimilate(facing_.view, tour::Turn{wrap180(heading - facing_.heading)}, v);
    facing_ = {v, heading};
  }

  void tell_tour_arrival(std::size_t p, int slot, std::size_t q, int qs, const EdgeRun& run) {
    const tour::ViewId arrived = nx_view(q, qs, true);
    if (tour_ != nullptr) {
      tour_->assimilate(nx_view(p, slot, false), tour::Travel{run.length, run.dtheta_deg}, arrived);
      // NX knows the place it arrived at (it matched it): TOUR hears so, through the place's first edge.
      const double first = map_.place(q).slots.at(0).heading_deg;
      tour_->recognise(arrived, wrap180(first - run.arrival_heading_deg), nx_view(q, 0, false));
    }
    facing_ = {arrived, run.arrival_heading_deg};
  }

  // Travels a known edge; false when it does not arrive at the place the map expects.
  bool travel_known(const Leg& leg) {
    const Slot& s = map_.place(leg.place).slots.at(static_cast<std::size_t>(leg.slot));
    const std::size_t q = s.to_place;
    const int qs = s.to_slot;
    tell_tour_departure(leg.place, leg.slot);
    robot_.read_heading();
    const EdgeRun run = follow_edge(robot_, s.heading_deg);
    std::optional<PlaceView> view;
    if (run.ending == EdgeEnding::arrived) view = describe_place(robot_);
    Arrival a = view ? identify_arrival(robot_, map_, *view, q) : Arrival{};
    if (!a.place) a = climb_again_at(robot_, map_, q, 2);
    if (a.expected) {
      tell_tour_arrival(leg.place, leg.slot, q, qs, run);
      stand_at(q);
      return true;
    }
    if (a.place) {
      // Somewhere else the map knows: re-localised there.
      count_failure(leg);
      stand_at(*a.place);
      facing_ = {nx_view(at_, 0, false), map_.place(at_).slots.at(0).heading_deg};
      return false;
    }
    // Nowhere known: back along the edge by dead reckoning.
    back_to(leg, run);
    return false;
  }

  void explore_slot(std::size_t p, int slot) {
    const NxConfig& c = robot_.config();
    tell_tour_departure(p, slot);
    robot_.read_heading();
    const double heading = map_.place(p).slots.at(static_cast<std::size_t>(slot)).heading_deg;
    const EdgeRun run = follow_edge(robot_, heading);
    const bool went_nowhere = run.displacement.norm() < 2 * c.step_mm;
    std::optional<PlaceView> view;
    if (run.ending == EdgeEnding::arrived && !went_nowhere) view = settled_view();
    const Arrival a = view ? identify_arrival(robot_, map_, *view, std::nullopt, p) : Arrival{};
    // The start itself, found again (an edge that turned back): not a place at the end of this edge.
    bool back_at_start = false;
    if (view && !a.place) {
      const auto near = map_.near(robot_.odometry(), robot_.position_radius(), *view, c.match_tolerance);
      back_at_start = std::find(near.begin(), near.end(), p) != near.end();
    }
    if (!view || back_at_start) {
      const SlotState state = run.ending == EdgeEnding::blocked ? SlotState::blocked : SlotState::open;
      map_.mark(p, slot, state);
      ++(state == SlotState::blocked ? report_.blocked_edges : report_.open_edges);
      if (climb_after_retrace(run)) stand_at(p);
      return;
    }
    if (a.place) {
      const std::size_t q = *a.place;
      ++report_.matches;
      const int qs = free_slot_toward(q, p, slot, run.arrival_heading_deg + 180);
      if (qs < 0) {
        // q has no free edge this way: its headings or this edge are misread. Knowing where it
        // stands matters more than the edge, which is given up.
        ++report_.arrivals_unlinked;
        map_.mark(p, slot, SlotState::open);
      } else {
        map_.link(p, slot, q, qs, run.length, run.dtheta_deg);
        tell_tour_arrival(p, slot, q, qs, run);
      }
      stand_at(q);
      return;
    }
    const int arrival = nearest_slot(*view, run.arrival_heading_deg + 180).first;
    const std::size_t n = new_place(*view);
    map_.link(p, slot, n, arrival, run.length, run.dtheta_deg);
    tell_tour_arrival(p, slot, n, arrival, run);
    at_ = n;
  }

  // The place where the robot stands, described, once its three ranges agree: a climb may stop on
  // its step limit off the vertex (a marble read from its neighbour's sector), and a place stored
  // there would be mm off. One more climb settles most; nullopt when it does not.
  std::optional<PlaceView> settled_view() {
    const NxConfig& c = robot_.config();
    const double allowed = 4 * c.place_tolerance_mm + 0.5 + 4 * c.range_error * 30 / std::sqrt(std::max(1, c.reads));
    const auto settled = [&](const std::optional<PlaceView>& v) {
      if (!v || v->marble_ranges.size() < 3) return false;
      const auto [lo, hi] = std::minmax_element(v->marble_ranges.begin(), v->marble_ranges.end());
      return *hi - *lo <= allowed;
    };
    std::optional<PlaceView> view = describe_place(robot_);
    if (settled(view)) return view;
    if (climb_to_place(robot_).ending != ClimbEnding::place) return std::nullopt;
    view = describe_place(robot_);
    return settled(view) ? view : std::nullopt;
  }

  // The slot of known place q by which an edge just travelled from (p, slot) arrives: the one
  // nearest `heading_deg` (within twice the heading tolerance) that is not explored toward another
  // place; -1 when none.
  int free_slot_toward(std::size_t q, std::size_t p, int slot, double heading_deg) const {
    const double tolerance = 2 * robot_.config().heading_tolerance_deg;
    const auto& slots = map_.place(q).slots;
    int best = -1;
    double best_off = tolerance;
    for (std::size_t k = 0; k < slots.size(); ++k) {
      const Slot& s = slots[k];
      if (s.state == SlotState::explored && (s.to_place != p || s.to_slot != slot)) continue;
      const double off = std::abs(wrap180(s.heading_deg - heading_deg));
      if (off <= best_off) {
        best = static_cast<int>(k);
        best_off = off;
      }
    }
    return best;
  }

  // NX knows it stands at place p: its odometry is anchored there.
  void stand_at(std::size_t p) {
    at_ = p;
    robot_.set_odometry(map_.place(p).position);
  }

  // Back from a known edge that did not arrive, by dead reckoning and a climb at its start.
  void back_to(const Leg& leg, const EdgeRun& run) {
    count_failure(leg);
    if (climb_after_retrace(run)) stand_at(leg.place);
  }

  // A known edge that failed: under range error once may be chance; after
  // config.failures_to_avoid failures neither direction is used again.
  void count_failure(const Leg& leg) {
    const Slot& s = map_.place(leg.place).slots.at(static_cast<std::size_t>(leg.slot));
    const std::pair<std::size_t, int> edge{std::min(leg.place, s.to_place),
                                           leg.place < s.to_place ? leg.slot : s.to_slot};
    if (++failures_[edge] < robot_.config().failures_to_avoid) return;
    failed_.insert({leg.place, leg.slot});
    failed_.insert({s.to_place, s.to_slot});
  }

  bool climb_after_retrace(const EdgeRun& run) {
    if (retrace(robot_, run).ending == ClimbEnding::place) return true;
    // Under range error a climb may run out of steps near the place: two more tries from where it
    // stopped before NX counts itself lost.
    for (int i = 0; i < 2; ++i) {
      if (climb_to_place(robot_).ending == ClimbEnding::place) return true;
    }
    lost_ = true;
    return false;
  }

  Robot& robot_;
  LearnedMap& map_;
  const ExploreSettings& settings_;
  tour::CognitiveMap* tour_;
  ExploreObserver* observer_;
  ExploreReport report_;
  std::size_t at_ = 0;
  Facing facing_;
  bool lost_ = false;
  int detours_ = 0;
  int forgiven_ = 0;
  std::map<std::pair<std::size_t, int>, int> failures_;  ///< per edge (its lower place's end)
  std::set<std::pair<std::size_t, int>> failed_;         ///< known edges avoided from now on
};

}  // namespace

ExploreReport explore(Robot& robot, LearnedMap& map, const ExploreSettings& settings, tour::CognitiveMap* tour,
                      ExploreObserver* observer) {
  return Exploration(robot, map, settings, tour, observer).run();
}

}  // namespace neopipe::nav::nx
