#include "nav/nx/explorer.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <utility>

namespace neopipe::nav::nx {

tour::ViewId nx_view(std::size_t place, int slot, bool arrived) {
  return static_cast<tour::ViewId>(place) * 64 + static_cast<tour::ViewId>(slot) * 2 + (arrived ? 1 : 0);
}

namespace {

// Known edges that may fail to lead where the map says before the exploration gives up.
constexpr int kMaxDetours = 50;

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
      const std::optional<Leg> next = nearest_unexplored();
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
  struct Trip {
    std::size_t place = 0;
    int slot = 0;
    EdgeRun out;
  };
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
    const std::size_t p = map_.add_place(view);
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
    if (run.ending != EdgeEnding::arrived) {
      avoid(leg.place, leg.slot);
      if (climb_after_retrace(run)) at_ = leg.place;
      return false;
    }
    const std::optional<PlaceView> view = describe_place(robot_);
    const NxConfig& c = robot_.config();
    if (!view) {
      lost_ = true;
      return false;
    }
    if (!map_.could_be(q, *view, c.match_tolerance, 2 * c.heading_tolerance_deg, 2)) {
      // Somewhere else: the best-fitting known place, if any.
      const std::vector<std::size_t> fits = map_.candidates(*view, c.match_tolerance, c.heading_tolerance_deg);
      if (fits.empty()) {
        // Nowhere known: back along the edge by dead reckoning, and avoid it from now on.
        avoid(leg.place, leg.slot);
        if (climb_after_retrace(run)) at_ = leg.place;
      } else {
        at_ = fits.front();
        facing_ = {nx_view(at_, 0, false), map_.place(at_).slots.at(0).heading_deg};
      }
      return false;
    }
    tell_tour_arrival(leg.place, leg.slot, q, qs, run);
    at_ = q;
    return true;
  }

  // The return trip that tests "here is place q": along another explored edge of q to its known
  // neighbour, then back. A trip that ends at a place unlike that neighbour refutes q; one that
  // ends at no place proves nothing (the next edge is tried). nullopt: nothing could be tested.
  std::optional<bool> test_match(std::size_t q, int arrival_slot) {
    const NxConfig& c = robot_.config();
    const auto& slots = map_.place(q).slots;
    for (std::size_t k = 0; k < slots.size(); ++k) {
      if (static_cast<int>(k) == arrival_slot || slots[k].state != SlotState::explored) continue;
      const std::size_t r = slots[k].to_place;
      robot_.read_heading();
      const EdgeRun out = follow_edge(robot_, slots[k].heading_deg);
      std::optional<PlaceView> there;
      if (out.ending == EdgeEnding::arrived) there = describe_place(robot_);
      const bool confirmed = there && map_.could_be(r, *there, c.match_tolerance, 2 * c.heading_tolerance_deg, 2);
      bool back = false;
      if (there) {
        const auto [back_slot, off] = nearest_slot(*there, out.arrival_heading_deg + 180);
        const EdgeRun home = follow_edge(robot_, there->slots[static_cast<std::size_t>(back_slot)]);
        back = home.ending == EdgeEnding::arrived && (home.displacement + out.displacement).norm() < 4 * c.step_mm;
        if (!back) retrace(robot_, home);
      }
      if (!back) retrace(robot_, out);
      if (confirmed && back) trip_ = Trip{q, static_cast<int>(k), out};
      if (!there || (confirmed && !back)) continue;  // inconclusive
      return confirmed;
    }
    return std::nullopt;
  }

  void explore_slot(std::size_t p, int slot) {
    const NxConfig& c = robot_.config();
    tell_tour_departure(p, slot);
    robot_.read_heading();
    const double heading = map_.place(p).slots.at(static_cast<std::size_t>(slot)).heading_deg;
    const EdgeRun run = follow_edge(robot_, heading);
    const bool went_nowhere = run.displacement.norm() < 2 * c.step_mm;
    std::optional<PlaceView> view;
    if (run.ending == EdgeEnding::arrived && !went_nowhere) view = describe_place(robot_);
    if (!view) {
      const SlotState state = run.ending == EdgeEnding::blocked ? SlotState::blocked : SlotState::open;
      map_.mark(p, slot, state);
      ++(state == SlotState::blocked ? report_.blocked_edges : report_.open_edges);
      if (climb_after_retrace(run)) at_ = p;
      return;
    }
    const int arrival = nearest_slot(*view, run.arrival_heading_deg + 180).first;
    for (const std::size_t q : map_.candidates(*view, c.match_tolerance, c.heading_tolerance_deg)) {
      if (q == p) continue;
      // q's slot toward where we came from must be free, or lead back to this very edge.
      const int qs = nearest_slot(map_.place(q).view, run.arrival_heading_deg + 180).first;
      const Slot& qslot = map_.place(q).slots.at(static_cast<std::size_t>(qs));
      if (qslot.state == SlotState::explored && (qslot.to_place != p || qslot.to_slot != slot)) continue;
      // (An open or blocked slot may be one that failed once: the edge just travelled says otherwise.)
      const std::optional<bool> test = test_match(q, qs);
      if (test.has_value() && !*test) {
        ++report_.matches_rejected;
        continue;
      }
      ++(test.has_value() ? report_.matches_confirmed : report_.matches_unconfirmed);
      map_.link(p, slot, q, qs, run.length, run.dtheta_deg);
      tell_tour_arrival(p, slot, q, qs, run);
      at_ = q;
      tell_tour_trip();
      return;
    }
    const std::size_t n = new_place(*view);
    map_.link(p, slot, n, arrival, run.length, run.dtheta_deg);
    tell_tour_arrival(p, slot, n, arrival, run);
    at_ = n;
  }

  // The confirming return trip is part of the experience: TOUR hears (q, k) -> (r, its slot) and
  // back, once the place it started from is known to be q.
  void tell_tour_trip() {
    if (!trip_) return;
    const Trip t = *trip_;
    trip_.reset();
    const Slot& s = map_.place(t.place).slots.at(static_cast<std::size_t>(t.slot));
    tell_tour_departure(t.place, t.slot);
    tell_tour_arrival(t.place, t.slot, s.to_place, s.to_slot, t.out);
    tell_tour_departure(s.to_place, s.to_slot);
    EdgeRun back;
    back.length = t.out.length;
    back.dtheta_deg = -t.out.dtheta_deg;
    back.arrival_heading_deg = wrap180(s.heading_deg + 180);
    tell_tour_arrival(s.to_place, s.to_slot, t.place, t.slot, back);
  }

  // A known edge that failed: neither direction is used again.
  void avoid(std::size_t p, int slot) {
    const Slot& s = map_.place(p).slots.at(static_cast<std::size_t>(slot));
    failed_.insert({p, slot});
    failed_.insert({s.to_place, s.to_slot});
  }

  bool climb_after_retrace(const EdgeRun& run) {
    if (retrace(robot_, run).ending == ClimbEnding::place) return true;
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
  std::set<std::pair<std::size_t, int>> failed_;  ///< known edges that did not lead where expected
  std::optional<Trip> trip_;
};

}  // namespace

ExploreReport explore(Robot& robot, LearnedMap& map, const ExploreSettings& settings, tour::CognitiveMap* tour,
                      ExploreObserver* observer) {
  return Exploration(robot, map, settings, tour, observer).run();
}

}  // namespace neopipe::nav::nx
