// `neopipe nav --system qualnav`: Qualnav's system through the rig from the command line — one
// journey, trials (the same JSON keys as the other systems', the same for one thread and two), the
// range-error and taught-route options, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace {
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

constexpr const char* kQualnavWorld =
    "size: [250, 250]\nmarble_diameter: 5\nobjects:\n  - [30, 40]\n  - [120, 30]\n  - [210, 50]\n  - [60, 120]\n"
    "  - [150, 110]\n  - [220, 150]\n  - [40, 210]\n  - [110, 190]\n  - [190, 220]\n  - [125, 145]\n";

class NavQualnavCli : public ScratchDirTest {
 protected:
  std::string world() {
    write_text(file("w.yaml"), kQualnavWorld);
    return file("w.yaml");
  }
  std::vector<std::string> qualnav(std::vector<std::string> extra) {
    std::vector<std::string> args{"nav", "--system", "qualnav", "--world", world()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  static void expect_one_line_error(const RunResult& r, int code, const std::string& words) {
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  }
};

}  // namespace

TEST_F(NavQualnavCli, HelpNamesTheSystemAndItsOptions) {
  const auto r = run_neopipe({"nav", "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* word : {"qualnav", "--range-error", "--taught-route", "detour"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  }
}

TEST_F(NavQualnavCli, OneJourneyReachesItsGoalAndClaimsIt) {
  const auto r = run_neopipe(qualnav({"--from", "0", "--to", "8", "--json", "--plot", file("j.png")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["system"], "qualnav");
  EXPECT_EQ(j["from"], 0);
  EXPECT_EQ(j["to"], 8);
  EXPECT_TRUE(j["reached_goal"].get<bool>()) << j.dump();
  EXPECT_EQ(j["ending"], "arrived");
  EXPECT_EQ(j["range_error"], 0.5);
  EXPECT_GT(j["memory_viewframes"].get<int>(), 5);
  EXPECT_GT(j["heading_steps"].get<int>(), 0);
  ASSERT_FALSE(j["held"].empty());
  EXPECT_EQ(j["held"].back()["entry"], 1);
  EXPECT_EQ(j["held"].back()["held"], 8);
  EXPECT_TRUE(j["held"].back()["correct"].get<bool>());
  EXPECT_LT(j["held"].back()["offset"].get<double>(), 2.0);  // the parallax range, not the 50 % estimate
  EXPECT_GT(std::filesystem::file_size(file("j.png")), 1000U);
  const auto text = run_neopipe(qualnav({"--from", "0", "--to", "8", "--taught-route", "detour"}));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("outcome: "), std::string::npos) << text.out;
}

TEST_F(NavQualnavCli, TrialsGiveTheSameJsonOnOneThreadAndTwo) {
  auto one = run_neopipe(qualnav({"--trials", "4", "--seed", "3", "--threads", "1", "--json", "--range-error", "1"}));
  auto two = run_neopipe(qualnav({"--trials", "4", "--seed", "3", "--threads", "2", "--json", "--range-error", "1"}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  json a = json::parse(one.out);
  json b = json::parse(two.out);
  for (const char* key : {"trials", "reached_goal", "reached_goal_rate", "reached_goal_ci95", "outcomes", "rates",
                          "ci95", "qualnav", "journeys", "mean_arm_travel", "frames"}) {
    EXPECT_TRUE(a.contains(key)) << key;
  }
  EXPECT_EQ(a["trials"], 4);
  EXPECT_EQ(a["qualnav"]["range_error"], 1.0);
  EXPECT_TRUE(a["qualnav"]["endings"].contains("blocked"));
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);
  const auto table = run_neopipe(qualnav({"--trials", "2"}));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("reached the goal"), std::string::npos) << table.out;
}

TEST_F(NavQualnavCli, BadInputIsOneLine) {
  write_text(file("one.yaml"), "size: [100, 100]\nobjects:\n  - [20, 20]\n");
  expect_one_line_error(run_neopipe({"nav", "--system", "qualnav", "--world", file("one.yaml"), "--trials", "2"}), 1,
                        "two marbles");
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--range-error", "-1"})), 2, "--range-error");
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--range-error", "nan"})), 2, "--range-error");
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--taught-route", "zigzag"})), 2, "--taught-route");
  expect_one_line_error(run_neopipe(qualnav({"--from", "0"})), 2, "--from and --to");
  expect_one_line_error(run_neopipe(qualnav({"--from", "0", "--to", "10"})), 2, "--to 10");
  expect_one_line_error(run_neopipe(qualnav({"--from", "3", "--to", "3"})), 2, "the start is the goal");
  expect_one_line_error(run_neopipe(qualnav({"--from", "0", "--to", "1", "--trials", "2"})), 2, "give either");
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--plot", file("p.png")})), 2, "--plot");
  expect_one_line_error(run_neopipe(qualnav({"--from", "0", "--to", "1", "--plot", file("p.txt")})), 2, ".png");
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--pairs", file("x.json")})), 2, "--pairs");
  expect_one_line_error(
      run_neopipe({"nav", "--system", "qrm", "--world", world(), "--trials", "2", "--range-error", "1"}), 2,
      "--system qualnav");
}

TEST_F(NavQualnavCli, RegionLevelRunsOneJourneyAndTrialsWithItsCounters) {
  const auto one =
      run_neopipe(qualnav({"--from", "0", "--to", "8", "--level", "regions", "--json", "--plot", file("regions.png")}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const json j = json::parse(one.out);
  EXPECT_EQ(j["level"], "regions");
  EXPECT_TRUE(j["reached_goal"].get<bool>()) << j.dump();
  ASSERT_TRUE(j["regions"].is_object()) << j.dump();
  for (const char* key : {"ending", "plan_regions", "regions_crossed", "shortcuts", "production_steps",
                          "fallback_steps", "fallbacks", "steps", "path_mm"}) {
    EXPECT_TRUE(j["regions"].contains(key)) << key;
  }
  EXPECT_GT(j["regions"]["production_steps"].get<int>(), 0) << j.dump();
  EXPECT_TRUE(std::filesystem::exists(file("regions.png")));
  const auto plain = run_neopipe(qualnav({"--from", "0", "--to", "8", "--json"}));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(json::parse(plain.out)["level"], "viewframes");
  EXPECT_TRUE(json::parse(plain.out)["regions"].is_null());

  auto a = json::parse(run_neopipe(qualnav({"--trials", "3", "--level", "regions", "--threads", "1", "--json"})).out);
  auto b = json::parse(run_neopipe(qualnav({"--trials", "3", "--level", "regions", "--threads", "2", "--json"})).out);
  EXPECT_EQ(a["qualnav"]["level"], "regions");
  ASSERT_TRUE(a["qualnav"].contains("regions")) << a.dump();
  for (const char* key : {"regions_crossed", "shortcuts", "fallbacks", "fallback_steps", "phase_endings"}) {
    EXPECT_TRUE(a["qualnav"]["regions"].contains(key)) << key;
  }
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);
  const auto table = run_neopipe(qualnav({"--trials", "2", "--level", "regions"}));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("region level:"), std::string::npos) << table.out;
}

TEST_F(NavQualnavCli, BadLevelIsOneLine) {
  expect_one_line_error(run_neopipe(qualnav({"--trials", "2", "--level", "hills"})), 2, "--level");
  expect_one_line_error(
      run_neopipe({"nav", "--system", "qrm", "--world", world(), "--trials", "2", "--level", "regions"}), 2,
      "--level goes with --system qualnav");
}
