// `neopipe nx explore` and `neopipe nav --system nx` (qualnav.md §9) on a small world: the learned
// map against the true Voronoi graph, journeys with the other systems' JSON keys, help, one-line
// errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_test_support.hpp"

namespace {
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

constexpr const char* kNxWorld =
    "size: [250, 250]\nmarble_diameter: 5\nobjects:\n  - [30, 40]\n  - [120, 30]\n  - [210, 50]\n  - [60, 120]\n"
    "  - [150, 110]\n  - [220, 150]\n  - [40, 210]\n  - [110, 190]\n  - [190, 220]\n  - [125, 145]\n";

class NxCli : public ScratchDirTest {
 protected:
  std::string world() {
    write_text(file("w.yaml"), kNxWorld);
    return file("w.yaml");
  }
  static void expect_one_line_error(const RunResult& r, int code, const std::string& words) {
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  }
};

TEST_F(NxCli, HelpNamesTheCommandsAndOptions) {
  const auto nav = run_neopipe({"nav", "--help"});
  ASSERT_EQ(nav.exit_code, 0) << nav.err;
  for (const char* word : {"nx", "--range-error", "--places"}) EXPECT_NE(nav.out.find(word), std::string::npos) << word;
  const auto nx = run_neopipe({"nx", "explore", "--help"});
  ASSERT_EQ(nx.exit_code, 0) << nx.err;
  for (const char* word : {"--world", "--range-error", "--places", "--plot", "--json"}) {
    EXPECT_NE(nx.out.find(word), std::string::npos) << word;
  }
}

TEST_F(NxCli, ExploreWithoutNoiseFindsTrueVertices) {
  const auto r = run_neopipe({"nx", "explore", "--world", world(), "--range-error", "0", "--sigma-move", "0",
                              "--sigma-rot", "0", "--json", "--plot", file("x.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["ending"], "agenda empty");
  EXPECT_GE(j["places"].get<int>(), 4);
  EXPECT_LE(j["truth"]["max_place_error_mm"].get<double>(), 2.0);
  EXPECT_EQ(j["truth"]["places_within_2mm"], j["places"]);
  EXPECT_EQ(j["truth"]["edges_wrong"], 0);
  EXPECT_EQ(j["tour_places"], j["places"]);
  EXPECT_GT(std::filesystem::file_size(file("x.png")), 1000U);
  const auto again = run_neopipe(
      {"nx", "explore", "--world", world(), "--range-error", "0", "--sigma-move", "0", "--sigma-rot", "0", "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  json a = json::parse(again.out);
  json b = j;
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);  // deterministic
}

TEST_F(NxCli, TrialsCarryTheSharedKeysAndOneJourneyReachesItsGoal) {
  const auto t =
      run_neopipe({"nav", "--system", "nx", "--world", world(), "--range-error", "0", "--trials", "4", "--json"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const json j = json::parse(t.out);
  for (const char* key : {"trials", "outcomes", "reached_goal", "reached_goal_rate", "reached_goal_ci95", "journeys"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["system"], "nx");
  EXPECT_TRUE(j["nx"].contains("endings"));
  EXPECT_EQ(j["journeys"].size(), 4U);
  const auto one = run_neopipe({"nav", "--system", "nx", "--world", world(), "--range-error", "0", "--sigma-move", "0",
                                "--sigma-rot", "0", "--from", "0", "--to", "8", "--json", "--plot", file("j.png")});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const json o = json::parse(one.out);
  EXPECT_TRUE(o["reached_goal"].get<bool>()) << o.dump();
  EXPECT_EQ(o["ending"], "arrived");
  EXPECT_GT(std::filesystem::file_size(file("j.png")), 1000U);
  const auto text =
      run_neopipe({"nav", "--system", "nx", "--world", world(), "--range-error", "0", "--from", "0", "--to", "8"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("outcome: "), std::string::npos) << text.out;
}

TEST_F(NxCli, BadInputIsOneLineNamingIt) {
  expect_one_line_error(run_neopipe({"nx", "explore", "--world", world(), "--range-error", "1.5"}), 2, "--range-error");
  expect_one_line_error(run_neopipe({"nx", "explore", "--world", world(), "--places", "0"}), 2, "--places");
  expect_one_line_error(run_neopipe({"nav", "--system", "nx", "--world", world(), "--trials", "2", "--places", "0"}), 2,
                        "--places");
  expect_one_line_error(
      run_neopipe({"nav", "--system", "nx", "--world", world(), "--trials", "2", "--plot", file("p.png")}), 2,
      "--plot");
  write_text(file("two.yaml"), "size: [100, 100]\nobjects:\n  - [20, 20]\n  - [60, 60]\n");
  expect_one_line_error(run_neopipe({"nx", "explore", "--world", file("two.yaml")}), 1, "three marbles");
  expect_one_line_error(run_neopipe({"nav", "--system", "nx", "--world", file("two.yaml"), "--trials", "2"}), 1,
                        "three marbles");
  expect_one_line_error(run_neopipe({"nx", "explore", "--world", file("missing.yaml")}), 1, "missing.yaml");
  expect_one_line_error(run_neopipe({"nav", "--system", "nx", "--world", world(), "--from", "0", "--to", "99"}), 2,
                        "--to 99");
}

}  // namespace
