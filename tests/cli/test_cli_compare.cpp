// `neopipe compare`: every system on the same pairs from the command line — the table, the JSON a
// user reads with jq or pandas, the same numbers for one thread and two, the plot, and bad input.

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

// Sixteen marbles about 36 mm apart on 160 x 160 mm: Park & Kender's 50 mm window connects most
// pairs, and QRM's tour of 8 images takes a fraction of a second.
constexpr const char* kCompareWorld =
    "size: [160, 160]\nmarble_diameter: 5\nobjects:\n  - [21.8, 20.2]\n  - [23.8, 56.9]\n  - [19.8, 95.8]\n"
    "  - [30.0, 136.6]\n  - [64.2, 21.7]\n  - [61.4, 58.3]\n  - [57.1, 92.3]\n  - [57.6, 138.1]\n  - [100.9, 28.7]\n"
    "  - [100.6, 57.3]\n  - [94.7, 98.5]\n  - [99.8, 137.3]\n  - [137.6, 20.0]\n  - [134.3, 63.1]\n  - [133.1, 93.1]\n"
    "  - [132.7, 128.1]\n";

class CompareCli : public ScratchDirTest {
 protected:
  std::vector<std::string> compare(std::vector<std::string> extra) {
    write_text(file("w.yaml"), kCompareWorld);
    std::vector<std::string> args{"compare", "--world", file("w.yaml"), "--sigma-map", "0.2", "--images", "8"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  static void expect_one_line_error(const RunResult& r, int code, const std::string& words) {
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  }
};

json without_times(json j) {
  j.erase("seconds");
  for (json& s : j["systems"]) s.erase("seconds");
  return j;
}

}  // namespace

TEST_F(CompareCli, HelpNamesTheSystemsAndOptions) {
  const auto r = run_neopipe({"compare", "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* word :
       {"--world", "--trials", "--systems", "park-kender", "qrm", "qualnav", "nx", "--json", "--plot"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word;
  }
}

TEST_F(CompareCli, JsonHasEverySystemOnTheSamePairsWhateverTheThreads) {
  const auto one = run_neopipe(compare({"--trials", "12", "--json", "--threads", "1"}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = run_neopipe(compare({"--trials", "12", "--json", "--threads", "2", "--plot", file("c.png")}));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const json j = json::parse(one.out);
  EXPECT_EQ(without_times(j), without_times(json::parse(two.out)));
  EXPECT_TRUE(std::filesystem::file_size(file("c.png")) > 1000);
  EXPECT_EQ(j["pairs"], 12);
  ASSERT_EQ(j["systems"].size(), 4U);
  EXPECT_EQ(j["systems"][0]["system"], "park-kender");
  EXPECT_EQ(j["systems"][1]["system"], "qrm");
  EXPECT_EQ(j["systems"][2]["system"], "qualnav");
  EXPECT_EQ(j["systems"][3]["system"], "nx");
  for (const json& s : j["systems"]) {
    EXPECT_EQ(s["journeys"], 12);
    const double rate = s["reached_goal_rate"].get<double>();
    EXPECT_GE(rate, s["reached_goal_ci95"][0].get<double>());
    EXPECT_LE(rate, s["reached_goal_ci95"][1].get<double>());
    EXPECT_FALSE(s["knows"].get<std::string>().empty());
  }
  ASSERT_EQ(j["mcnemar"].size(), 6U);  // every two of the four
  EXPECT_EQ(j["mcnemar"][0]["a"], "park-kender");
}

TEST_F(CompareCli, TablePrintsOneRowPerSystem) {
  const auto r = run_neopipe(compare({"--trials", "4", "--systems", "qrm"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("qrm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("KNOWS BEFOREHAND"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("park-kender "), std::string::npos) << r.out;
}

TEST_F(CompareCli, BadInputIsOneLineNamingIt) {
  expect_one_line_error(run_neopipe(compare({"--systems", "qrm,magic"})), 2, "magic");
  expect_one_line_error(run_neopipe(compare({"--systems", "qrm,qrm"})), 2, "twice");
  expect_one_line_error(run_neopipe(compare({"--trials", "0"})), 2, "--trials");
  expect_one_line_error(run_neopipe(compare({"--trials", "2", "--nx-range-error", "1.5"})), 2, "--nx-range-error");
  expect_one_line_error(run_neopipe(compare({"--trials", "2", "--plot", file("c.jpg")})), 2, "c.jpg");
  expect_one_line_error(run_neopipe({"compare", "--world", file("missing.yaml"), "--trials", "2"}), 1, "missing.yaml");
}
