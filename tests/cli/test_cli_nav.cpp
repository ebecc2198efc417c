// `neopipe nav`: the navigator in the simulator from the command line — one journey, trials, their
// determinism, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace {
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

// Three marbles in a row a step apart and one far away: 0 -> 2 is a short route that an error-free
// navigator must follow; 3 cannot be reached from anywhere.
constexpr const char* kSmallWorld =
    "size: [200, 200]\nmarble_diameter: 5\nobjects:\n  - [100, 100]\n  - [125, 115]\n  - [150, 140]\n"
    "  - [40, 160]\n";

class NavCli : public ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // Calibration sessions cached where this test cleans up, not in the user's cache.
    ::setenv("NEOPIPE_CACHE_DIR", file("cache").c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  }
  std::string small_world() {
    write_text(file("small.yaml"), kSmallWorld);
    return file("small.yaml");
  }
  std::string default_world() {
    const auto r = run_neopipe({"sim", "world", "--objects", "100", "--seed", "1", "--out", file("w.yaml")});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return file("w.yaml");
  }
};

}  // namespace

TEST_F(NavCli, HelpNamesTheOptions) {
  const auto r = run_neopipe({"nav", "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* option : {"--world",
                             "--from",
                             "--to",
                             "--cost",
                             "--sigma-map",
                             "--sigma-move",
                             "--sigma-rot",
                             "--seed",
                             "--trials",
                             "--no-recovery",
                             "--window",
                             "--json",
                             "--plot",
                             "--video",
                             "--realism",
                             "--calibration-cache",
                             "--no-calibration-cache",
                             "--min-reliability",
                             "--navigator",
                             "--as-trial",
                             "--descriptions",
                             "--reliability-diagram"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
}

TEST_F(NavCli, OneErrorFreeJourneyOnASmallWorldSucceeds) {
  const std::string world = small_world();
  const auto r = run_neopipe({"nav", "--world", world, "--from", "0", "--to", "2", "--sigma-map", "0", "--sigma-move",
                              "0", "--sigma-rot", "0", "--json", "--plot", file("p.png"), "--video", file("v.avi")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["from"], 0);
  EXPECT_EQ(j["to"], 2);
  EXPECT_EQ(j["outcome"], "success_direct");
  EXPECT_TRUE(j["reached_goal"].get<bool>());
  EXPECT_EQ(j["ending"], "arrived");
  EXPECT_GT(j["frames"].get<int>(), 0);
  ASSERT_FALSE(j["entries"].empty());
  const json& last = j["entries"].back()["truth"];
  EXPECT_EQ(last["held"], 2);
  EXPECT_TRUE(last["correct"].get<bool>());
  EXPECT_GT(fs::file_size(file("p.png")), 0U);
  EXPECT_GT(fs::file_size(file("v.avi")), 0U);

  const auto text = run_neopipe({"nav", "--world", world, "--from", "0", "--to", "2"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("custom map:"), std::string::npos);
  EXPECT_NE(text.out.find("outcome: "), std::string::npos);
  // Without --sigma-map the map-maker's survey goes through the rig: global camera, engine, calibration.
  EXPECT_NE(text.out.find("survey: global camera (rig realism) + calibration"), std::string::npos);
}

TEST_F(NavCli, LandmarkBasedPathsCanBeFollowed) {
  const auto r = run_neopipe({"nav", "--world", small_world(), "--from", "0", "--to", "2", "--cost", "landmark",
                              "--sigma-map", "0", "--sigma-move", "0", "--sigma-rot", "0", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["cost"], "landmark");
  EXPECT_GT(j["planned"]["landmark_distance"].get<double>(), 0);
  EXPECT_EQ(j["outcome"], "success_direct");
}

TEST_F(NavCli, TrialsCountEveryJourneyOnceAndRepeatBySeed) {
  const std::string world = default_world();
  const auto run = [&](const std::string& threads) {
    const auto r =
        run_neopipe({"nav", "--world", world, "--trials", "20", "--seed", "7", "--json", "--threads", threads});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    json j = json::parse(r.out);
    // Wall-clock figures differ between runs; everything else must not.
    j.erase("seconds");
    j.erase("frames_per_second");
    return j;
  };
  const json a = run("1");
  EXPECT_EQ(a["trials"], 20);
  int total = 0;
  for (const auto& [name, count] : a["outcomes"].items()) {
    total += count.get<int>();
    const auto ci = a["ci95"][name];
    const double rate = a["rates"][name].get<double>();
    EXPECT_LE(ci[0].get<double>(), rate) << name;
    EXPECT_GE(ci[1].get<double>(), rate) << name;
  }
  EXPECT_EQ(total, 20);
  ASSERT_EQ(a["journeys"].size(), 20U);
  int direct = 0;
  for (const auto& journey : a["journeys"]) {
    EXPECT_NE(journey["from"], journey["to"]);
    direct += journey["outcome"] == "success_direct" ? 1 : 0;
  }
  EXPECT_EQ(direct, a["outcomes"]["success_direct"].get<int>());
  EXPECT_EQ(a["outcomes"].size(), 6U);
  EXPECT_GT(a["frames"].get<int>(), 0);
  EXPECT_EQ(a["survey"]["method"], "global_camera");
  EXPECT_GT(a["survey"]["sigma"].get<double>(), 0);
  EXPECT_LT(a["survey"]["rms_error"].get<double>(), 0.05);
  EXPECT_GT(a["mean_planned_reliability"].get<double>(), 0.5);
  EXPECT_LE(a["mean_planned_reliability"].get<double>(), 1.0);
  EXPECT_EQ(a["cost"], "reliability");  // the default: a journey's job is to arrive
  EXPECT_EQ(run("2"), a);               // same seed, any thread count: the same journeys
}

// Both cameras' realism is chosen on the command line; the survey says which it used. The global
// camera's calibration session is cached: the second run reads it, a corrupt entry is recalibrated
// with a note, and --no-calibration-cache writes nothing.
TEST_F(NavCli, RealismAndTheCalibrationCache) {
  const std::string world = small_world();
  const auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"nav", "--world", world, "--from", "0", "--to", "2", "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_neopipe(args);
  };
  const auto rig = run({});
  ASSERT_EQ(rig.exit_code, 0) << rig.err;
  const json a = json::parse(rig.out);
  EXPECT_EQ(a["survey"]["realism"], "rig");
  EXPECT_EQ(a["survey"]["board_thickness"], 3.0);
  EXPECT_LT(a["survey"]["rms_error"].get<double>(), 0.05);
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(file("cache"))) entries.push_back(e.path());
  ASSERT_EQ(entries.size(), 1U);

  const auto again = run({});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(json::parse(again.out)["survey"], a["survey"]);  // the same session, read back

  write_text(entries[0].string(), "%YAML:1.0\n---\nmodel: [\n");
  const auto corrupt = run({});
  ASSERT_EQ(corrupt.exit_code, 0) << corrupt.err;
  EXPECT_NE(corrupt.err.find("corrupt cached calibration"), std::string::npos) << corrupt.err;
  EXPECT_EQ(json::parse(corrupt.out)["survey"], a["survey"]);

  const auto ideal = run({"--realism", "ideal", "--calibration-cache", file("other")});
  ASSERT_EQ(ideal.exit_code, 0) << ideal.err;
  EXPECT_EQ(json::parse(ideal.out)["survey"]["realism"], "ideal");
  EXPECT_TRUE(fs::exists(file("other")));
  const auto uncached = run({"--no-calibration-cache", "--calibration-cache", file("none")});
  ASSERT_EQ(uncached.exit_code, 0) << uncached.err;
  EXPECT_FALSE(fs::exists(file("none")));
  EXPECT_TRUE(one_error_line(run({"--realism", "real"}), "--realism"));
}

TEST_F(NavCli, BadInputIsOneLineError) {
  const std::string world = small_world();
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--from", "0", "--to", "9"}), "9"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--from", "1", "--to", "1"}), "same object"));
  const auto unreachable = run_neopipe({"nav", "--world", world, "--from", "0", "--to", "3"});
  EXPECT_EQ(unreachable.exit_code, 3);
  EXPECT_TRUE(one_error_line(unreachable, "cannot be reached"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--trials", "0"}), "--trials 0"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--trials", "2", "--sigma-map", "-1"}), "-1"));
  // Two touching marbles are one blob to the global camera: the survey says so instead of guessing.
  write_text(file("touching.yaml"), "size: [200, 200]\nobjects:\n  - [100, 100]\n  - [105, 100]\n  - [40, 40]\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", file("touching.yaml"), "--trials", "2"}), "global camera"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world}), "--trials"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", file("missing.yaml"), "--trials", "2"}), "missing.yaml"));
  write_text(file("bad.yaml"), "size: [200, 200]\nobjects: [[1, 2\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", file("bad.yaml"), "--trials", "2"}), "bad.yaml"));
  EXPECT_TRUE(one_error_line(
      run_neopipe({"nav", "--world", world, "--from", "0", "--to", "2", "--plot", file("p.gif")}), "p.gif"));
}

// --survey-csv: every object's surveyed place beside its true one, the error their distance; with
// --sigma-map 0 the survey is the truth. An unwritable path is a one-line error.
TEST_F(NavCli, SurveyCsvListsWhatTheMapMakerBelieved) {
  const std::string world = small_world();
  for (const char* sigma : {"0", "1"}) {
    const auto r = run_neopipe({"nav", "--world", world, "--from", "0", "--to", "2", "--sigma-map", sigma,
                                "--survey-csv", file("survey.csv")});
    // Written before the journey, whatever becomes of it (a wrong survey may leave it lost).
    if (std::string(sigma) == "0") {
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    ASSERT_TRUE(fs::exists(file("survey.csv"))) << r.err;
    std::istringstream csv(slurp(file("survey.csv")));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "id,x,y,true_x,true_y,error");
    int rows = 0;
    double largest = 0;
    while (std::getline(csv, line)) {
      std::vector<double> v;
      std::istringstream fields(line);
      for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
      ASSERT_EQ(v.size(), 6U) << line;
      EXPECT_EQ(v[0], rows);
      EXPECT_NEAR(std::hypot(v[1] - v[3], v[2] - v[4]), v[5], 1e-3);
      largest = std::max(largest, v[5]);
      ++rows;
    }
    EXPECT_EQ(rows, 4);
    if (std::string(sigma) == "0") {
      EXPECT_EQ(largest, 0.0);
    } else {
      EXPECT_GT(largest, 0.1);
    }
  }
  EXPECT_TRUE(one_error_line(
      run_neopipe({"nav", "--world", world, "--from", "0", "--to", "2", "--survey-csv", file("no/such/dir/s.csv")}),
      "--survey-csv"));
}

// --min-reliability: routes forecast below it are refused. In trials they are counted apart, not as
// failures; alone, the journey exits 3 with one line. --as-trial replays one journey of the trials
// exactly, --reliability-diagram draws their forecast against their outcome, --navigator paper runs
// the paper's navigator.
TEST_F(NavCli, RefusalsReplaysDiagramsAndThePapersNavigator) {
  const std::string world = default_world();
  const auto r = run_neopipe({"nav", "--world", world, "--trials", "20", "--sigma-map", "1.5", "--min-reliability",
                              "0.95", "--json", "--reliability-diagram", file("d.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  const int refused = j["refused"].get<int>();
  EXPECT_GT(refused, 0);
  EXPECT_LT(refused, 20);
  EXPECT_EQ(j["run"].get<int>(), 20 - refused);
  int backtracks = 0;
  for (const auto& journey : j["journeys"]) backtracks += journey["backtracks"].get<int>();
  EXPECT_EQ(j["recoveries"]["backtracks"].get<int>(), backtracks);
  EXPECT_GE(j["recoveries"]["qoc_rules"].get<int>(), 0);
  int outcomes = 0;
  for (const auto& [name, count] : j["outcomes"].items()) outcomes += count.get<int>();
  EXPECT_EQ(outcomes, 20 - refused);
  std::optional<json> refused_journey, run_journey;
  int index = 0, run_index = 0;
  for (const auto& journey : j["journeys"]) {
    if (journey["outcome"] == "refused") {
      EXPECT_LT(journey["planned_reliability"].get<double>(), 0.95);
      if (!refused_journey) refused_journey = journey;
    } else if (!run_journey) {
      run_journey = journey;
      run_index = index;
    }
    ++index;
  }
  ASSERT_TRUE(refused_journey && run_journey);
  EXPECT_TRUE(std::filesystem::file_size(file("d.png")) > 1000);

  const auto alone = run_neopipe({"nav", "--world", world, "--sigma-map", "1.5", "--min-reliability", "0.95", "--from",
                                  std::to_string((*refused_journey)["from"].get<int>()), "--to",
                                  std::to_string((*refused_journey)["to"].get<int>())});
  EXPECT_EQ(alone.exit_code, 3);
  EXPECT_TRUE(one_error_line(alone, "refused"));

  const auto replay = run_neopipe(
      {"nav", "--world", world, "--sigma-map", "1.5", "--json", "--as-trial", std::to_string(run_index), "--from",
       std::to_string((*run_journey)["from"].get<int>()), "--to", std::to_string((*run_journey)["to"].get<int>())});
  ASSERT_EQ(replay.exit_code, 0) << replay.err;
  const json one = json::parse(replay.out);
  EXPECT_EQ(one["outcome"], (*run_journey)["outcome"]);
  EXPECT_EQ(one["frames"], (*run_journey)["frames"]);

  const auto paper =
      run_neopipe({"nav", "--world", world, "--trials", "5", "--sigma-map", "0.25", "--navigator", "paper", "--json"});
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  EXPECT_EQ(json::parse(paper.out)["navigator"], "paper");

  // The paper's descriptions only: no journey's steps are Far or Near.
  const auto papers_map = run_neopipe(
      {"nav", "--world", world, "--trials", "20", "--sigma-map", "1.5", "--descriptions", "paper", "--json"});
  ASSERT_EQ(papers_map.exit_code, 0) << papers_map.err;
  const json pm = json::parse(papers_map.out);
  EXPECT_EQ(pm["descriptions"], "paper");
  for (const auto& journey : pm["journeys"]) {
    for (const auto& step : journey["steps"]) {
      const std::string name = step["step"];
      EXPECT_EQ(name.find("FAR"), std::string::npos) << name;
      EXPECT_EQ(name.find("NEAR"), std::string::npos) << name;
    }
  }
  EXPECT_EQ(j["descriptions"], "extended");
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--trials", "2", "--descriptions", "all"}),
                             "--descriptions"));

  EXPECT_TRUE(
      one_error_line(run_neopipe({"nav", "--world", world, "--trials", "2", "--navigator", "compass"}), "--navigator"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--trials", "2", "--min-reliability", "1.5"}),
                             "--min-reliability"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--trials", "2", "--as-trial", "1"}), "--as-trial"));
  EXPECT_TRUE(one_error_line(run_neopipe({"nav", "--world", world, "--from", "0", "--to", "1", "--as-trial", "-1"}),
                             "--as-trial"));
  EXPECT_TRUE(one_error_line(
      run_neopipe({"nav", "--world", world, "--from", "0", "--to", "1", "--reliability-diagram", file("x.png")}),
      "--reliability-diagram"));
}
