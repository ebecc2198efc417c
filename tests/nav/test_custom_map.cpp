// The custom map's text grammar (park-kender.md §8): the paper's examples read and write back.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "nav/common/custom_map.hpp"

namespace neopipe::nav {
namespace {

TEST(CustomMap, ReadsThePapersFig17Entry) {
  const CustomMap m = parse_custom_map("((Isol, (4, SW, Isol), (2, SE, Isol), (3, -), SW))");
  ASSERT_EQ(m.entries.size(), 1u);
  const MapEntry& e = m.entries[0];
  EXPECT_EQ(e.seek, Description::Isol);
  EXPECT_FALSE(e.slide);
  EXPECT_EQ(e.adjust, Corner::SW);
  ASSERT_EQ(e.rules.size(), 3u);
  EXPECT_EQ(e.verified_qoc(), 3);
  ASSERT_NE(e.recovery_for(4), nullptr);
  EXPECT_EQ(e.recovery_for(4)->corner, Corner::SW);
  EXPECT_EQ(e.recovery_for(2)->corner, Corner::SE);
  EXPECT_EQ(e.recovery_for(1), nullptr);
  EXPECT_EQ(format_custom_map(m), "((Isol, (4, SW, Isol), (2, SE, Isol), (3, -), SW))");
}

TEST(CustomMap, ReadsThePapersSection634MapWithATrajectoryAndAGoal) {
  // §6.3.4, as printed (no spaces).
  const CustomMap m = parse_custom_map("((Isol,SE),(Isol,NE),(Isol,NE),(Isol,Trajp,(2,NW,Isol),(1,-),-))");
  ASSERT_EQ(m.entries.size(), 4u);
  EXPECT_EQ(m.entries[3].slide, Direction::positive);
  EXPECT_FALSE(m.entries[3].adjust);
  EXPECT_EQ(m.entries[3].verified_qoc(), 1);
  EXPECT_EQ(parse_custom_map(format_custom_map(m)), m);
  EXPECT_EQ(format_entry(m.entries[0]), "(Isol, SE)");
  EXPECT_EQ(parse_custom_map("((*, SW), (Obvious, Trajn, -))").entries[1].slide, Direction::negative);
}

TEST(CustomMap, RandomMapsRoundTrip) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 500; ++trial) {
    CustomMap m;
    const int n = static_cast<int>(rng() % 6);
    for (int i = 0; i < n; ++i) {
      MapEntry e;
      e.seek = static_cast<Description>(rng() % 5);
      if (rng() % 3 == 0) {
        e.slide = rng() % 2 ? Direction::positive : Direction::negative;
        if (rng() % 2) e.slide_limit = 1 + static_cast<double>(rng() % 500);
        if (rng() % 2) {
          const auto mm = [&](int lo, int span) { return static_cast<double>(lo + static_cast<int>(rng() % span)); };
          e.slide_goal = SlideGoal{mm(-300, 600), mm(-60, 120), mm(1, 40), mm(1, 80)};
        }
      }
      const int rules = static_cast<int>(rng() % 4);
      for (int r = 0; r < rules; ++r) {
        RecoveryRule rule = RecoveryRule::verified(static_cast<int>(rng() % 5));
        if (rng() % 4) {
          rule.corner = kCorners[rng() % 4];
          rule.seek = static_cast<Description>(rng() % 5);
        } else {
          rule.only_in_doubt = rng() % 2 == 0;
          if (rng() % 2) {
            QuadrantPattern q{};
            for (Occupancy& o : q) o = static_cast<Occupancy>(rng() % 3);
            const auto occupied = std::count(q.begin(), q.end(), Occupancy::occupied);
            rule.qoc = static_cast<int>(occupied + rng() % (std::count(q.begin(), q.end(), Occupancy::unsure) + 1));
            rule.quadrants = q;
          }
        }
        e.rules.push_back(rule);
      }
      if (rng() % 5) e.adjust = kCorners[rng() % 4];
      m.entries.push_back(e);
    }
    ASSERT_EQ(parse_custom_map(format_custom_map(m)), m) << format_custom_map(m);
  }
}

TEST(CustomMap, ReadsASlidesBoundAndAQocToMeasureOnlyInDoubt) {
  const CustomMap m = parse_custom_map("((*, SW), (Obvious, Trajn:82, (2, ?), SE), (Isol, Trajp, (1, -), -))");
  ASSERT_EQ(m.entries.size(), 3U);
  EXPECT_EQ(m.entries[1].slide, Direction::negative);
  EXPECT_EQ(m.entries[1].slide_limit, 82.0);
  EXPECT_EQ(m.entries[1].verified_qoc(), 2);
  EXPECT_TRUE(m.entries[1].verify_only_in_doubt());
  EXPECT_FALSE(m.entries[2].slide_limit.has_value());
  EXPECT_FALSE(m.entries[2].verify_only_in_doubt());
  EXPECT_EQ(format_custom_map(m), "((*, SW), (Obvious, Trajn:82, (2, ?), SE), (Isol, Trajp, (1, -), -))");
  EXPECT_THROW(parse_custom_map("((Obvious, Trajp:0, SE))"), CustomMapError);
  EXPECT_THROW(parse_custom_map("((Obvious, Trajp:1.5, SE))"), CustomMapError);
  EXPECT_THROW(parse_custom_map("((Obvious, Trajp:, SE))"), CustomMapError);
}

TEST(CustomMap, ReadsWhereASlidesGoalShouldEnter) {
  const CustomMap m = parse_custom_map("((*, SW), (Near, Trajp:78@73/-9~19/21, SW), (Isol, Trajn@5/24~13/13, -))");
  ASSERT_EQ(m.entries.size(), 3U);
  EXPECT_EQ(m.entries[1].slide_limit, 78.0);
  EXPECT_EQ(m.entries[1].slide_goal, (SlideGoal{73, -9, 19, 21}));
  EXPECT_FALSE(m.entries[2].slide_limit.has_value());
  EXPECT_EQ(m.entries[2].slide_goal, (SlideGoal{5, 24, 13, 13}));
  EXPECT_EQ(format_custom_map(m), "((*, SW), (Near, Trajp:78@73/-9~19/21, SW), (Isol, Trajn@5/24~13/13, -))");
  // The goal's place admits what lies within both tolerances; beyond it along the track, the goal
  // must have gone by.
  const SlideGoal& g = *m.entries[1].slide_goal;
  EXPECT_TRUE(g.admits(73 + 19, -9 - 21));
  EXPECT_FALSE(g.admits(73 + 20, -9));
  EXPECT_FALSE(g.admits(73, -9 + 22));
  EXPECT_FALSE(g.passed(73 + 19));
  EXPECT_TRUE(g.passed(73 + 20));
  for (const char* bad :
       {"((Isol, Trajp:78@73/-9~19, SW))", "((Isol, Trajp:78@73/-9~0/4, SW))", "((Isol, Trajp:78@73/-9~19/4x, SW))",
        "((Isol, Trajp:78@, SW))", "((Isol, Trajp:78@73.5/-9~19/4, SW))", "((Isol, Trajp:@73/-9~19/4, SW))"}) {
    EXPECT_THROW(parse_custom_map(bad), CustomMapError) << bad;
  }
}

TEST(CustomMap, ReadsTheQuadrantsOfAVerifiedQoc) {
  const CustomMap m = parse_custom_map("((*, SW), (Isol, (2 NE ~SE SW, ?), -), (Near, (0 none, -), SW))");
  const std::optional<QuadrantPattern> q = m.entries[1].verified_quadrants();
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ((*q)[index(Corner::NE)], Occupancy::occupied);
  EXPECT_EQ((*q)[index(Corner::SW)], Occupancy::occupied);
  EXPECT_EQ((*q)[index(Corner::SE)], Occupancy::unsure);
  EXPECT_EQ((*q)[index(Corner::NW)], Occupancy::empty);
  EXPECT_EQ(m.entries[1].verified_qoc(), 2);
  EXPECT_EQ(m.entries[2].verified_quadrants(), (QuadrantPattern{}));
  // Written in the corners' order (SE, SW, NE, NW).
  EXPECT_EQ(format_custom_map(m), "((*, SW), (Isol, (2 ~SE SW NE, ?), -), (Near, (0 none, -), SW))");
  EXPECT_FALSE(parse_custom_map("((Isol, (2, -), SW))").entries[0].verified_quadrants().has_value());
}

TEST(CustomMap, MalformedTextNamesWhereAndWhat) {
  const auto message = [](const std::string& text) {
    try {
      parse_custom_map(text);
    } catch (const CustomMapError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("((Isol, XX))"),
            "custom map: at character 11: expected a corner (SE, SW, NE, NW) or -, found 'XX'");
  EXPECT_EQ(message("((Isol, (2, XX), SW))"),
            "custom map: at character 15: expected a corner (SE, SW, NE, NW), - or ?, found 'XX'");
  EXPECT_EQ(message("((Isle, SW))"),
            "custom map: at character 7: expected a description (Obvious, Isol, Far, Near or *), found 'Isle'");
  EXPECT_EQ(message("((Isol, (7, SW, Isol), SW))"), "custom map: at character 11: expected a QOC 0..4, found '7'");
  EXPECT_EQ(message("((Isol, SW)"), "custom map: at character 12: expected ')', found 'the end'");
  EXPECT_EQ(message("((Isol, SW)) extra"), "custom map: at character 14: expected end of the map, found 'e'");
  EXPECT_EQ(message("((Isol, (3 NE SW, -), SW))"),
            "custom map: at character 12: expected quadrants that a QOC of 3 can count, found 'SW NE'");
  EXPECT_EQ(message("((Isol, (1 NE NE, -), SW))"),
            "custom map: at character 17: expected each quadrant once, found 'NE'");
  EXPECT_EQ(message("((Isol, (1 N, -), SW))"),
            "custom map: at character 13: expected a quadrant (SE, SW, NE, NW, ~ before an unsure one) or none, "
            "found 'N'");
  EXPECT_EQ(message("((Isol, (1 NE, SW, Isol), SW))"),
            "custom map: at character 18: expected - or ? after the quadrants of the verified QOC, found 'SW'");
  EXPECT_EQ(
      message("((Isol, Trajp:70@60/-4~8, SW))"),
      "custom map: at character 25: expected a slide goal along/cross~along-tolerance/cross-tolerance in whole mm "
      "(tolerances > 0), found '60/-4~8'");
  EXPECT_EQ(message("((Isol, (2, -), Trajp, SW))"),
            "custom map: at character 22: expected a recovery rule or a corner, found 'Trajp'");
}

}  // namespace
}  // namespace neopipe::nav
