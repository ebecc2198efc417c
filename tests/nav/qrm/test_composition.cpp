// Composition (spec qrm.md §4): the committed table's count and entries, its symmetries, branch and
// bound agreeing with it, random configurations never outside it, and the table file's errors.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "nav/qrm/composition.hpp"
#include "nav/qrm/edc.hpp"
#include "nav/qrm/operators.hpp"

namespace {
using namespace neopipe::nav::qrm;  // NOLINT(google-build-using-namespace)

const CompositionTable& table() {
  return composition_table();
}

StateSet mirror(StateSet set) {
  StateSet out;
  for (const State s : set) out.insert(neopipe::nav::qrm::mirror(s));
  return out;
}

std::string table_text() {
  return format_composition_table(table().entries());
}

std::string parse_error(const std::string& text) {
  try {
    parse_composition_table(text, "bad.txt");
  } catch (const CompositionTableError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(QrmComposition, CountsAndEntriesOfTheSpec) {
  EXPECT_EQ(table().feasible_triples(), 2214);
  std::set<std::pair<State, State>> singletons;
  for (State a = 1; a <= kStateCount; ++a) {
    for (State b = 1; b <= kStateCount; ++b) {
      const int n = table()(a, b).count();
      EXPECT_GE(n, 1) << a << "," << b;
      EXPECT_LE(n, 16) << a << "," << b;
      if (n == 1) singletons.emplace(a, b);
    }
  }
  const std::set<std::pair<State, State>> expected{{5, 10},  {5, 16},  {6, 15},  {9, 12}, {10, 5},
                                                   {10, 11}, {11, 10}, {11, 16}, {16, 5}, {16, 11}};
  EXPECT_EQ(singletons, expected);
  EXPECT_EQ(table()(1, 17), StateSet::range(5, 20));
  EXPECT_EQ(table()(1, 1), (StateSet{1, 5, 11, 19}));
  EXPECT_EQ(table()(7, 7), (StateSet{7, 8, 13, 14}));
}

TEST(QrmComposition, AllIsAbsorbingAndMirrorsCommute) {
  for (State s = 1; s <= kStateCount; ++s) {
    EXPECT_TRUE(table()(StateSet{s}, StateSet::all()).is_all()) << s;
    EXPECT_TRUE(table()(StateSet::all(), StateSet{s}).is_all()) << s;
    for (State t = 1; t <= kStateCount; ++t) {
      EXPECT_EQ(table()(neopipe::nav::qrm::mirror(s), neopipe::nav::qrm::mirror(t)), mirror(table()(s, t)))
          << s << "," << t;
    }
  }
}

TEST(QrmComposition, SetCompositionIsTheUnionOfEntries) {
  std::mt19937_64 rng(4);
  std::uniform_int_distribution<StateSet::Mask> mask(0, StateSet::kAllMask);
  for (int n = 0; n < 2000; ++n) {
    const StateSet x = StateSet::from_mask(mask(rng) & mask(rng));
    const StateSet y = StateSet::from_mask(mask(rng) & mask(rng));
    StateSet expected;
    for (const State a : x) {
      for (const State b : y) expected |= table()(a, b);
    }
    EXPECT_EQ(table()(x, y), expected);
  }
  EXPECT_EQ(table()(StateSet{}, StateSet::all()), StateSet{});
}

TEST(QrmComposition, WorkedExampleOfSection4) {
  const Eigen::Vector2d a{0, 0};
  const Eigen::Vector2d b{1, -1};
  const Eigen::Vector2d c{6, -1};
  const Eigen::Vector2d d{2, -6};
  const StateSet ca_b{6, 7};
  const StateSet cb_d{5};
  EXPECT_TRUE(ca_b.contains(classify(c, a, b)));
  EXPECT_EQ(classify(c, b, d), 5);
  const StateSet ab_c = left_shift(ca_b);
  const StateSet bc_d = inverse(cb_d);
  EXPECT_EQ(ab_c, (StateSet{1, 5, 11}));
  EXPECT_EQ(bc_d, StateSet{16});
  EXPECT_EQ(table()(1, 16), (StateSet{1, 2}));
  EXPECT_EQ(table()(5, 16), StateSet{1});
  EXPECT_EQ(table()(11, 16), StateSet{1});
  EXPECT_EQ(table()(ab_c, bc_d), (StateSet{1, 2}));
  EXPECT_EQ(classify(a, b, d), 2);
}

// Regenerating all 400 entries takes about half a minute on one core (docs/qrm.md: `neopipe qrm
// tables --write`); a seeded sample of entries, each redone in full by branch and bound, keeps the
// test short while any entry may be drawn.
TEST(QrmComposition, BranchAndBoundReproducesASeededSampleOfEntries) {
  std::mt19937_64 rng(2214);
  std::uniform_int_distribution<State> state(1, kStateCount);
  for (int n = 0; n < 24; ++n) {
    const State s1 = state(rng);
    const State s2 = state(rng);
    StateSet entry;
    for (State s3 = 1; s3 <= kStateCount; ++s3) {
      const Feasibility f = composition_feasible(s1, s2, s3);
      if (!f.witness) continue;
      entry.insert(s3);
      // The witness is a real configuration with these states.
      const Point4& w = *f.witness;
      const Eigen::Vector2d a{0, 0};
      const Eigen::Vector2d b{0, 1};
      const Eigen::Vector2d c{w[0], w[1]};
      const Eigen::Vector2d d{w[2], w[3]};
      EXPECT_EQ(classify(a, b, c), s1);
      EXPECT_EQ(classify(b, c, d), s2);
      EXPECT_EQ(classify(a, b, d), s3);
    }
    EXPECT_EQ(entry, table()(s1, s2)) << "comp(" << s1 << ", " << s2 << ")";
  }
}

TEST(QrmComposition, RandomConfigurationsAreNeverOutsideTheTable) {
  // A = (0,0), B = (0,1); C and D uniform in [-8, 8]^2 half of the time, else within a log-uniform
  // distance of A, B or C, so that the small regions near the segment are hit too.
  std::mt19937_64 rng(1e8);
  std::uniform_real_distribution<double> box(-8, 8);
  std::uniform_real_distribution<double> unit(0, 1);
  const Eigen::Vector2d a{0, 0};
  const Eigen::Vector2d b{0, 1};
  const auto near = [&](const Eigen::Vector2d& centre) {
    const double r = std::pow(10.0, -2 + 3 * unit(rng));
    const double t = 2 * M_PI * unit(rng);
    return Eigen::Vector2d(centre + r * Eigen::Vector2d(std::cos(t), std::sin(t)));
  };
  std::set<int> seen;
  for (int n = 0; n < 1500000; ++n) {
    const Eigen::Vector2d c = n % 2 == 0 ? Eigen::Vector2d(box(rng), box(rng)) : near(n % 4 == 1 ? a : b);
    const Eigen::Vector2d d = n % 3 == 0 ? Eigen::Vector2d(box(rng), box(rng)) : near(n % 3 == 1 ? c : b);
    const State s1 = classify(a, b, c);
    const State s2 = classify(b, c, d);
    const State s3 = classify(a, b, d);
    if (s1 == 0 || s2 == 0 || s3 == 0) continue;
    ASSERT_TRUE(table()(s1, s2).contains(s3)) << "AB:C " << s1 << ", BC:D " << s2 << ", AB:D " << s3;
    seen.insert((s1 * 21 + s2) * 21 + s3);
  }
  // Most of the table is reached (the rest are thin regions), so the check is not vacuous.
  EXPECT_GT(seen.size(), 2000U);
  // The library's own sampler (behind `neopipe qrm tables --sample N`) agrees.
  const SamplingReport report = sample_composition(table(), 500000, 9);
  EXPECT_EQ(report.outside, 0);
  EXPECT_EQ(report.samples, 500000);
  EXPECT_GT(report.triples_seen, 1900);
  // ... and finds what a table lacks: comp(1, 1) without 19.
  CompositionEntries broken = table().entries();
  broken[0][0] = StateSet{1, 5, 11};
  const SamplingReport bad = sample_composition(CompositionTable(broken), 500000, 9);
  EXPECT_GT(bad.outside, 0);
  EXPECT_EQ(bad.first_outside, (std::array<State, 3>{1, 1, 19}));
}

TEST(QrmComposition, TheFileFormatRoundTrips) {
  const std::string text = table_text();
  EXPECT_EQ(parse_composition_table(text, "t"), table().entries());
  // The committed file is exactly what the library writes.
  std::ifstream committed(std::string(NEOPIPE_QRM_SOURCE_DIR) + "/composition_table.txt");
  std::stringstream file;
  file << committed.rdbuf();
  EXPECT_EQ(file.str(), text);
  const std::string path = (std::filesystem::temp_directory_path() / "neopipe_qrm_table_test.txt").string();
  std::ofstream(path) << text;
  EXPECT_EQ(load_composition_table(path), table().entries());
  std::filesystem::remove(path);
}

TEST(QrmComposition, CorruptOrMismatchedFilesAreOneLineErrorsNamingTheFile) {
  const std::string good = table_text();
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  const auto expect_error = [](const std::string& message, const std::string& cause) {
    EXPECT_EQ(message.rfind("bad.txt", 0), 0U) << message << " (expected: " << cause << ")";
    EXPECT_NE(message.find(cause), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expect_error(parse_error(replaced("\n1 1 1,5,11,19\n", "\n1 1 1,5,11\n")), "checksum mismatch");
  expect_error(parse_error(replaced("neopipe-qrm-composition 1", "neopipe-qrm-composition 2")), "format version 2");
  expect_error(parse_error(replaced("box 8 depth 40", "box 8 depth 36")), "depth 36");
  expect_error(parse_error(replaced("\n1 2 ", "\n1 3 ")), "expected the entry of (1, 2)");
  expect_error(parse_error(replaced("\n1 1 1,5,11,19\n", "\n1 1 1,5,x\n")), "not a list of states");
  expect_error(parse_error(replaced("\n1 1 1,5,11,19\n", "\n1 1 5,1\n")), "not strictly increasing");
  expect_error(parse_error(good.substr(0, good.find("\n10 1 ") + 1)), "truncated");
  expect_error(parse_error(good + "1 1 1\n"), "after the checksum");
  expect_error(parse_error("hello\n"), "not a composition table");
  expect_error(parse_error(""), "empty");
  try {
    load_composition_table("/nonexistent/qrm.txt");
    ADD_FAILURE();
  } catch (const CompositionTableError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/qrm.txt: cannot open"), std::string::npos);
  }
}
