// `neopipe nav --system qrm`: the qualitative relational map's system through the rig from the
// command line — one journey, trials (the same JSON keys as Park & Kender's, the same for one
// thread and two), another run's pairs, and bad input.

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

// Ten marbles on 250 x 250 mm: small enough for a tour of 8 images to take a fraction of a second.
constexpr const char* kWorld =
    "size: [250, 250]\nmarble_diameter: 5\nobjects:\n  - [30, 40]\n  - [120, 30]\n  - [210, 50]\n  - [60, 120]\n"
    "  - [150, 110]\n  - [220, 150]\n  - [40, 210]\n  - [110, 190]\n  - [190, 220]\n  - [125, 145]\n";

class NavQrmCli : public ScratchDirTest {
 protected:
  std::string world() {
    write_text(file("w.yaml"), kWorld);
    return file("w.yaml");
  }
  std::vector<std::string> qrm(std::vector<std::string> extra) {
    std::vector<std::string> args{"nav", "--system", "qrm", "--world", world(), "--images", "8"};
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

TEST_F(NavQrmCli, HelpNamesTheSystemAndItsOptions) {
  const auto r = run_neopipe({"nav", "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* word : {"--system", "qrm", "park-kender", "--images", "--k", "--pairs"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  }
}

TEST_F(NavQrmCli, OneJourneyReachesItsGoal) {
  const auto r = run_neopipe(qrm({"--from", "0", "--to", "8", "--json", "--plot", file("j.png")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["system"], "qrm");
  EXPECT_EQ(j["from"], 0);
  EXPECT_EQ(j["to"], 8);
  EXPECT_TRUE(j["reached_goal"].get<bool>()) << j.dump();
  EXPECT_EQ(j["ending"], "arrived");
  EXPECT_EQ(j["planned_route"].front(), 0);
  EXPECT_EQ(j["planned_route"].back(), 8);
  EXPECT_EQ(j["reached"].back(), 8);
  EXPECT_GT(j["steps"].get<int>(), 0);
  EXPECT_TRUE(j["held"].back()["correct"].get<bool>());
  EXPECT_GT(std::filesystem::file_size(file("j.png")), 1000U);
  const auto text = run_neopipe(qrm({"--from", "0", "--to", "8"}));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("outcome: "), std::string::npos) << text.out;
}

TEST_F(NavQrmCli, TrialsGiveTheSameJsonOnOneThreadAndTwo) {
  auto one = run_neopipe(qrm({"--trials", "4", "--seed", "3", "--threads", "1", "--json"}));
  auto two = run_neopipe(qrm({"--trials", "4", "--seed", "3", "--threads", "2", "--json"}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  json a = json::parse(one.out);
  json b = json::parse(two.out);
  for (const char* key : {"trials", "reached_goal", "reached_goal_rate", "reached_goal_ci95", "outcomes", "rates",
                          "ci95", "qrm", "journeys"}) {
    EXPECT_TRUE(a.contains(key)) << key;
  }
  EXPECT_EQ(a["trials"], 4);
  EXPECT_TRUE(a["qrm"]["endings"].contains("step_limit"));
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);
  // Another run's pairs: the same journeys, in order.
  write_text(file("t.json"), one.out);
  const auto again = run_neopipe(qrm({"--pairs", file("t.json"), "--seed", "3", "--json"}));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const json c = json::parse(again.out);
  ASSERT_EQ(c["journeys"].size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c["journeys"][i]["from"], a["journeys"][i]["from"]);
    EXPECT_EQ(c["journeys"][i]["to"], a["journeys"][i]["to"]);
  }
  const auto table = run_neopipe(qrm({"--trials", "2"}));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("reached the goal"), std::string::npos) << table.out;
}

TEST_F(NavQrmCli, BadInputIsOneLine) {
  write_text(file("two.yaml"), "size: [100, 100]\nobjects:\n  - [20, 20]\n  - [80, 80]\n");
  expect_one_line_error(run_neopipe({"nav", "--system", "qrm", "--world", file("two.yaml"), "--trials", "2"}), 1,
                        "three marbles");
  expect_one_line_error(run_neopipe(qrm({"--trials", "2", "--images", "0"})), 2, "--images");
  expect_one_line_error(run_neopipe(qrm({"--trials", "2", "--k", "2"})), 2, "--k");
  expect_one_line_error(run_neopipe(qrm({"--from", "0"})), 2, "--from and --to");
  expect_one_line_error(run_neopipe(qrm({"--from", "0", "--to", "10"})), 2, "--to 10");
  expect_one_line_error(run_neopipe(qrm({"--from", "3", "--to", "3"})), 2, "the start is the goal");
  expect_one_line_error(run_neopipe(qrm({"--from", "0", "--to", "1", "--trials", "2"})), 2, "give one of");
  expect_one_line_error(run_neopipe(qrm({"--trials", "2", "--plot", file("p.png")})), 2, "--plot");
  expect_one_line_error(run_neopipe(qrm({"--from", "0", "--to", "1", "--plot", file("p.txt")})), 2, ".png");
  write_text(file("junk.json"), "{\"x\": 1}");
  expect_one_line_error(run_neopipe(qrm({"--pairs", file("junk.json")})), 1, "not a trials JSON");
  expect_one_line_error(run_neopipe(qrm({"--pairs", file("missing.json")})), 1, "cannot open");
  expect_one_line_error(run_neopipe({"nav", "--world", world(), "--trials", "2", "--pairs", file("junk.json")}), 2,
                        "--pairs goes with --system qrm");
  expect_one_line_error(run_neopipe({"nav", "--system", "other", "--world", world(), "--trials", "2"}), 2, "--system");
}
