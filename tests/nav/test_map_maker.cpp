// The map-maker end to end: routes on hand-made and random worlds, replayed step by step with the
// shared descriptors as an error-free navigator would, checked against brute force.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <optional>
#include <random>

#include "nav/mapmaker/map_maker.hpp"

namespace neopipe::nav::mapmaker {
namespace {

using Eigen::Vector2d;

Workspace random_workspace(int n, double side, std::uint64_t seed, double min_gap = 8) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(2, side - 2);
  Workspace w{{side, side}, {}};
  while (static_cast<int>(w.objects.size()) < n) {
    const Vector2d p(u(rng), u(rng));
    bool free = true;
    for (const Vector2d& q : w.objects) free = free && (p - q).norm() >= min_gap;
    if (free) w.objects.push_back(p);
  }
  return w;
}

// What an error-free navigator does with the custom map: returns the object it ends on and the
// window travel, or nullopt when an entry cannot be carried out.
struct Replay {
  std::uint32_t end = 0;
  double travel = 0;
};
std::optional<Replay> replay(const WorldViews& views, std::uint32_t start, const CustomMap& map) {
  if (map.entries.empty() || map.entries[0].seek != Description::Any || !map.entries[0].adjust) return std::nullopt;
  Placement at{start, *map.entries[0].adjust};
  Replay r;
  for (std::size_t k = 1; k < map.entries.size(); ++k) {
    const MapEntry& e = map.entries[k];
    const auto found = views.landmark(at, e.seek);
    if (!found) return std::nullopt;
    std::uint32_t landmark = *found;
    Vector2d window = views.origin(at);
    if (e.slide) {
      Vector2d d = (views.position(landmark) - views.position(at.object)).normalized();
      if (*e.slide == Direction::negative) d = -d;
      const auto hit = first_entering(views.grid(), views.window(), window, d, views.position(at.object));
      if (!hit) return std::nullopt;
      landmark = hit->object;
      window += hit->slide * d;
      r.travel += hit->slide;
    }
    // Verification: the landmark reached must show the QOC the map expects.
    if (const auto q = e.verified_qoc()) {
      if (views.qoc(landmark) != *q) return std::nullopt;
    }
    if (!e.adjust) {
      if (k + 1 != map.entries.size()) return std::nullopt;
      r.end = landmark;
      return r;
    }
    at = {landmark, *e.adjust};
    r.travel += (views.origin(at) - window).norm();
  }
  return std::nullopt;
}

TEST(MapMaker, RoutesReplayToTheGoalWithTheirDistanceOnRandomWorlds) {
  int routes = 0;
  int unreachable = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const MapMaker maker(random_workspace(60, 300, seed), MapMakerOptions{});
    std::mt19937 rng(static_cast<unsigned>(seed));
    for (int trial = 0; trial < 15; ++trial) {
      const std::uint32_t a = rng() % 60;
      const std::uint32_t b = (a + 1 + rng() % 59) % 60;
      for (const CostCriterion c : kCriteria) {
        Route route;
        try {
          route = maker.plan(a, b, c);
        } catch (const UnreachableGoal&) {
          ++unreachable;
          continue;
        }
        ++routes;
        const auto r = replay(maker.views(), a, route.custom_map);
        ASSERT_TRUE(r) << a << "->" << b << " " << format_custom_map(route.custom_map);
        EXPECT_EQ(r->end, b);
        EXPECT_NEAR(r->travel, route.distance, 1e-9 * (1 + route.distance));
        double u = 0;
        for (const RouteStep& s : route.steps) u += s.step.unreliability();
        EXPECT_NEAR(u, route.unreliability, 1e-12);
      }
    }
  }
  EXPECT_GT(routes, 100);
  std::cout << routes << " routes replayed, " << unreachable << " unreachable\n";
}

// The extended descriptions (docs/navigation.md, "Descriptions") add steps and take none away: a
// Far or Near step names another object than the paper's description at its placement, and the most
// reliable route can only be as reliable or more.
TEST(MapMaker, FarAndNearStepsExtendThePapersAndNeverMakeTheBestRouteWorse) {
  const Workspace w = random_workspace(120, 400, 5, 6);
  const WorldViews views(w, WindowModel{});
  const NavigatorErrors errors;
  const StepTable paper(views, errors, false);
  const StepTable extended(views, errors, true);
  const auto is_extension = [](const Step& s) { return s.seek == Description::Far || s.seek == Description::Near; };
  int added = 0;
  for (const Step& s : paper.steps()) EXPECT_FALSE(is_extension(s));
  for (const Step& s : extended.steps()) {
    if (!is_extension(s)) continue;
    ++added;
    EXPECT_EQ(views.landmark(s.from, s.seek), s.via);
    const auto primary = views.obvious(s.from) ? views.obvious(s.from) : views.isolated(s.from);
    EXPECT_NE(primary, s.via) << "a Far or Near step that names the paper's landmark adds nothing";
    EXPECT_GT(s.reliability, 0);
    EXPECT_LE(s.reliability, 1);
  }
  EXPECT_EQ(extended.steps().size() - static_cast<std::size_t>(added), paper.steps().size());
  EXPECT_GT(added, 100);

  MapMakerOptions with;
  with.errors.sigma = 1.5;
  MapMakerOptions without = with;
  without.extended_descriptions = false;
  const MapMaker rich(w, with);
  const MapMaker plain(w, without);
  int compared = 0;
  int better = 0;
  for (std::uint32_t a = 0; a < 120; a += 5) {
    const std::uint32_t b = (a * 53 + 17) % 120;
    if (a == b) continue;
    try {
      const Route r = rich.plan(a, b, CostCriterion::reliability);
      const Route p = plain.plan(a, b, CostCriterion::reliability);
      EXPECT_LE(r.unreliability, p.unreliability + 1e-12) << a << "->" << b;
      better += r.unreliability < p.unreliability - 1e-9 ? 1 : 0;
      ++compared;
    } catch (const UnreachableGoal&) {
    }
  }
  EXPECT_GT(compared, 10);
  EXPECT_GT(better, 0) << "the extension never helped";
}

// The steps leaving a placement are listed farthest landmark first: the planner breaks ties by
// insertion order, so that is the preference among equal routes (tests/mutation/mutants.json, N22).
TEST(MapMaker, StepsLeavingAPlacementComeFarthestLandmarkFirst) {
  const Workspace w = random_workspace(120, 400, 5, 6);
  const WorldViews views(w, WindowModel{});
  const StepTable table(views, NavigatorErrors{}, true);
  int compared = 0;
  for (std::uint32_t node = 0; node < 4 * views.object_count(); ++node) {
    const auto [first, last] = table.range(node);
    for (std::uint32_t i = first; i + 1 < last; ++i) {
      const Step& a = table.steps()[i];
      const Step& b = table.steps()[i + 1];
      ASSERT_GE(a.landmark_distance, b.landmark_distance) << "node " << node << ", steps " << i << " and " << i + 1;
      compared += a.landmark_distance > b.landmark_distance ? 1 : 0;
    }
  }
  EXPECT_GT(compared, 50);
}

TEST(MapMaker, TheThreeCriteriaOrderAsThePaperFinds) {
  const MapMaker maker(random_workspace(150, 400, 42, 6), MapMakerOptions{});
  int compared = 0;
  for (std::uint32_t a = 0; a < 150; a += 7) {
    const std::uint32_t b = (a * 37 + 11) % 150;
    if (a == b) continue;
    try {
      const Route d = maker.plan(a, b, CostCriterion::distance);
      const Route u = maker.plan(a, b, CostCriterion::reliability);
      const Route r = maker.plan(a, b, CostCriterion::ratio);
      EXPECT_LE(d.distance, r.distance + 1e-9);
      EXPECT_LE(d.distance, u.distance + 1e-9);
      EXPECT_LE(u.unreliability, r.unreliability + 1e-12);
      EXPECT_LE(u.unreliability, d.unreliability + 1e-12);
      // The compromise the map-maker minimises counts a look at the goal as a window's travel:
      // (D + a) e^U (map_maker.cpp).
      const auto compromise = [](const Route& route) {
        return (route.distance + WindowModel{}.side) * std::exp(route.unreliability);
      };
      EXPECT_LE(compromise(r), compromise(d) * (1 + 1e-12));
      EXPECT_LE(compromise(r), compromise(u) * (1 + 1e-12));
      ++compared;
    } catch (const UnreachableGoal&) {
    }
  }
  EXPECT_GT(compared, 5);
}

TEST(MapMaker, LandmarkBasedAndContextBasedShortestPathsDiffer) {
  // From 0 to 2 (window 50 mm, margin 2.5). Object 3 is 47.5 mm from 0 but already in the window of
  // (0, SW); holding it at SE moves the window by (-1, 18) and brings 2 into view. Object 1 is only
  // 22.7 mm from 0, on the other side: it is in view from (0, SE), and holding it at SW, the corner
  // that looks towards 2, moves the window by (28, 15). Every step is an obvious parkway step.
  const Workspace w{{160, 160}, {{106, 29}, {89, 44}, {123, 89}, {150, 47}}};
  const MapMaker maker(w, MapMakerOptions{});
  const Route by_d = maker.plan(0, 2, CostCriterion::distance);
  const Route by_l = maker.plan(0, 2, CostCriterion::landmark);
  EXPECT_EQ(format_custom_map(by_d.custom_map), "((*, SW), (Obvious, (2 SW NW, ?), SE), (Obvious, (2 SE SW, ?), -))");
  EXPECT_NEAR(by_d.distance, std::hypot(1, 18), 1e-9);
  EXPECT_NEAR(by_d.landmark_distance, std::hypot(44, 18) + std::hypot(27, 42), 1e-9);
  EXPECT_EQ(format_custom_map(by_l.custom_map), "((*, SE), (Obvious, (2 SE NE, ?), SW), (Obvious, (2 SE SW, ?), -))");
  EXPECT_NEAR(by_l.distance, std::hypot(28, 15), 1e-9);
  EXPECT_NEAR(by_l.landmark_distance, std::hypot(17, 15) + std::hypot(34, 45), 1e-9);
  ASSERT_EQ(by_l.steps.size(), 2U);
  EXPECT_EQ(by_l.steps[0].step.landmark, 1U);
  EXPECT_EQ(by_l.criterion, CostCriterion::landmark);
  // The table's cost column is what the criterion adds up.
  EXPECT_NE(route_table(by_l).find("22.672"), std::string::npos) << route_table(by_l);
  const auto end = replay(maker.views(), 0, by_l.custom_map);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->end, 2U);
  EXPECT_NEAR(end->travel, by_l.distance, 1e-9);
}

// Landmark-based planning (the paper's foil, §7.2) minimises L and so never beats context-based
// planning on D, nor loses to it on L; the route still reports the window travel it really costs.
TEST(MapMaker, LandmarkRoutesMinimiseLandmarkDistanceAndDistanceRoutesTheTravel) {
  int compared = 0, differ = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const MapMaker maker(random_workspace(120, 400, seed, 6), MapMakerOptions{});
    std::mt19937 rng(static_cast<unsigned>(seed));
    for (int trial = 0; trial < 60; ++trial) {
      const std::uint32_t a = rng() % 120;
      const std::uint32_t b = (a + 1 + rng() % 119) % 120;
      Route by_d, by_l;
      try {
        by_d = maker.plan(a, b, CostCriterion::distance);
      } catch (const UnreachableGoal&) {
        EXPECT_THROW(maker.plan(a, b, CostCriterion::landmark), UnreachableGoal);
        continue;
      }
      by_l = maker.plan(a, b, CostCriterion::landmark);
      ++compared;
      EXPECT_LE(by_l.landmark_distance, by_d.landmark_distance + 1e-9) << a << "->" << b;
      EXPECT_LE(by_d.distance, by_l.distance + 1e-9) << a << "->" << b;
      double d = 0, l = 0;
      for (const RouteStep& s : by_l.steps) {
        d += s.distance;
        l += s.step.landmark_distance;
      }
      EXPECT_NEAR(by_l.distance, d, 1e-9 * (1 + d));
      EXPECT_NEAR(by_l.landmark_distance, l, 1e-9 * (1 + l));
      if (by_l.distance > by_d.distance + 1e-9) ++differ;
    }
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(differ, 5);  // else the two criteria would not have been told apart
}

TEST(MapMaker, ShortestRouteEqualsBruteForceOverAllSimpleStepSequences) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const MapMaker maker(random_workspace(7, 110, seed, 10), MapMakerOptions{});
    const std::vector<Step>& steps = maker.steps().steps();
    for (std::uint32_t a = 0; a < 7; ++a) {
      for (std::uint32_t b = 0; b < 7; ++b) {
        if (a == b) continue;
        // Depth-first over simple paths of placements.
        double best = std::numeric_limits<double>::infinity();
        std::vector<bool> used(28, false);
        std::function<void(std::uint32_t, double)> walk = [&](std::uint32_t node, double d) {
          const auto [begin, end] = maker.steps().range(node);
          for (std::uint32_t i = begin; i < end; ++i) {
            const Step& s = steps[i];
            if (s.landmark == b) {
              best = std::min(best, d + s.arrival_travel);
              continue;
            }
            const std::uint32_t next = Placement{s.landmark, s.adjust}.node();
            if (used[next]) continue;
            used[next] = true;
            walk(next, d + s.travel);
            used[next] = false;
          }
        };
        for (const Corner c : kCorners) {
          used.assign(28, false);
          used[Placement{a, c}.node()] = true;
          walk(Placement{a, c}.node(), 0);
        }
        if (std::isinf(best)) {
          EXPECT_THROW(maker.plan(a, b, CostCriterion::distance), UnreachableGoal);
        } else {
          EXPECT_NEAR(maker.plan(a, b, CostCriterion::distance).distance, best, 1e-9) << seed << " " << a << " " << b;
        }
      }
    }
  }
}

TEST(MapMaker, ChainOfObviousLandmarksGivesTheObviousMap) {
  // Four objects 30 mm apart going North-East in a wide world: each sees only the next one.
  const Workspace w{{400, 400}, {{100, 100}, {130, 130}, {160, 160}, {190, 190}}};
  const MapMaker maker(w, MapMakerOptions{});
  const Route r = maker.plan(0, 3, CostCriterion::reliability);
  EXPECT_DOUBLE_EQ(r.unreliability, 0.0);  // every step obvious
  for (const RouteStep& s : r.steps) EXPECT_EQ(s.check.kind, Verifiability::trivial);
  const auto end = replay(maker.views(), 0, r.custom_map);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->end, 3u);
}

TEST(MapMaker, RejectsBadRequestsAndSaysWhenTheGoalIsUnreachable) {
  // Two pairs 300 mm apart on a diagonal: no window holds both, and no trajectory direction of
  // one pair (along its own axis) meets the other.
  const Workspace w{{600, 600}, {{50, 50}, {50, 70}, {400, 550}, {420, 550}}};
  const MapMaker maker(w, MapMakerOptions{});
  EXPECT_THROW(maker.plan(0, 0, CostCriterion::distance), MapError);
  EXPECT_THROW(maker.plan(0, 9, CostCriterion::distance), MapError);
  EXPECT_THROW(maker.plan(0, 2, CostCriterion::distance), UnreachableGoal);
  EXPECT_NO_THROW(maker.plan(0, 1, CostCriterion::distance));
}

// A survey may list the marbles in any order; the routes between the same two marbles must not
// change with it. Object ids reach every part of the map-maker (grids, views, the reference's place
// in a view, step tables, planner nodes and their tie-breaks), so a part that leans on index order
// (a neighbour counted only one way, a view that depends on which object came first) gives another
// route, another custom map or another cost once the ids are shuffled.
TEST(MapMaker, RoutesDoNotDependOnTheOrderTheObjectsAreListedIn) {
  const Workspace w = random_workspace(80, 300, 5);
  std::vector<std::uint32_t> id(w.objects.size());  // id[i]: object i's id in the shuffled world
  std::iota(id.begin(), id.end(), 0U);
  std::shuffle(id.begin(), id.end(), std::mt19937_64(7));
  Workspace shuffled{w.size, std::vector<Vector2d>(w.objects.size())};
  for (std::size_t i = 0; i < id.size(); ++i) shuffled.objects[id[i]] = w.objects[i];
  const MapMaker a(w, MapMakerOptions{});
  const MapMaker b(shuffled, MapMakerOptions{});
  int compared = 0;
  for (const CostCriterion c : kCriteria) {
    for (std::uint32_t from = 0; from < 80; from += 9) {
      for (std::uint32_t to = 1; to < 80; to += 13) {
        if (from == to) continue;
        SCOPED_TRACE(testing::Message() << criterion_name(c) << " from " << from << " to " << to);
        std::optional<Route> ra;
        try {
          ra = a.plan(from, to, c);
        } catch (const UnreachableGoal&) {
          EXPECT_THROW(b.plan(id[from], id[to], c), UnreachableGoal);
          continue;
        }
        const Route rb = b.plan(id[from], id[to], c);
        ++compared;
        EXPECT_EQ(format_custom_map(ra->custom_map), format_custom_map(rb.custom_map));
        EXPECT_EQ(ra->start_corner, rb.start_corner);
        EXPECT_NEAR(ra->distance, rb.distance, 1e-9 * (1 + ra->distance));
        EXPECT_NEAR(ra->unreliability, rb.unreliability, 1e-9 * (1 + ra->unreliability));
        EXPECT_NEAR(ra->forecast, rb.forecast, 1e-9);
        ASSERT_EQ(ra->steps.size(), rb.steps.size());
        for (std::size_t k = 0; k < ra->steps.size(); ++k) {
          EXPECT_EQ(id[ra->steps[k].step.landmark], rb.steps[k].step.landmark) << "step " << k;
        }
      }
    }
  }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace neopipe::nav::mapmaker

namespace neopipe::nav::mapmaker {
namespace {

// An unverifiable goal still carries its QOC, to be measured on arrival: a wrong goal that shows
// another QOC sends the navigator back instead of ending an unaware failure. Unverifiable steps on
// the way carry none (measured there, it finds more mistakes than it can undo).
TEST(MapMaker, AnUnverifiableGoalCarriesItsQocForArrival) {
  MapMakerOptions o;
  o.errors.sigma = 1.5;
  o.border_tolerance = 6.6;
  const MapMaker maker(random_workspace(150, 400, 42, 6), o);
  int goals = 0, on_the_way = 0;
  for (std::uint32_t a = 0; a < 150; a += 3) {
    const std::uint32_t b = (a * 37 + 11) % 150;
    if (a == b) continue;
    try {
      const Route r = maker.plan(a, b, CostCriterion::reliability);
      for (std::size_t k = 0; k < r.steps.size(); ++k) {
        if (r.steps[k].check.kind != Verifiability::unverifiable) continue;
        const MapEntry& e = r.custom_map.entries[k + 1];
        if (k + 1 == r.steps.size()) {
          ++goals;
          EXPECT_EQ(e.verified_qoc(), r.steps[k].check.qoc);
          EXPECT_TRUE(e.verify_only_in_doubt());
          EXPECT_FALSE(e.adjust.has_value());
        } else {
          ++on_the_way;
          EXPECT_FALSE(e.verified_qoc().has_value());
        }
      }
    } catch (const UnreachableGoal&) {
    }
  }
  EXPECT_GT(goals, 0);
  EXPECT_GT(on_the_way, 0);
}

}  // namespace
}  // namespace neopipe::nav::mapmaker
