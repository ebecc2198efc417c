// `neopipe map`: the map-maker from the command line — its JSON, text, plots and bad input.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "nav/common/custom_map.hpp"

namespace {
namespace fs = std::filesystem;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

class MapCli : public ScratchDirTest {
 protected:
  void make_world(int objects = 100, int seed = 1) {
    const auto r = run_neopipe({"sim", "world", "--objects", std::to_string(objects), "--seed", std::to_string(seed),
                                "--out", file("w.yaml")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
};

}  // namespace

TEST_F(MapCli, JsonHasParkwaysQocTrajectoriesAndARoute) {
  make_world();
  const auto all = run_neopipe({"map", "--world", file("w.yaml"), "--json"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const json j = json::parse(all.out);
  ASSERT_EQ(j["qoc"].size(), 100U);
  for (const auto& q : j["qoc"]) EXPECT_TRUE(q.get<int>() >= 0 && q.get<int>() <= 4);
  std::size_t in_parkways = 0;
  for (const auto& p : j["parkways"]["general"]) in_parkways += p.size();
  EXPECT_EQ(in_parkways, 100U);  // every object in exactly one general parkway
  for (const auto& e : j["parkways"]["obvious"]) {
    ASSERT_EQ(e.size(), 3U);
    const std::string c = e[1];
    EXPECT_TRUE(c == "SE" || c == "SW" || c == "NE" || c == "NW");
  }
  EXPECT_GE(j["parkways"]["isolated"].size(), j["parkways"]["obvious"].size());
  ASSERT_GT(j["trajectories"].size(), 0U);
  for (const auto& t : j["trajectories"]) {
    EXPECT_TRUE(t["dir"] == "p" || t["dir"] == "n");
    EXPECT_NE(t["from"], t["to"]);
  }
  EXPECT_LE(j["strongly_connected"]["with_trajectories"].get<int>(), j["strongly_connected"]["parkways"].get<int>());
  EXPECT_FALSE(j.contains("path"));
  EXPECT_EQ(j["border_tolerance"], 0.0);  // by default the map-maker takes its positions as exact

  // A route between the two objects farthest apart that are reachable.
  int routes = 0;
  for (int to = 1; to < 100 && routes < 3; to += 7) {
    const auto r = run_neopipe(
        {"map", "--world", file("w.yaml"), "--json", "--from", "0", "--to", std::to_string(to), "--cost", "distance"});
    if (r.exit_code == 3) continue;  // unreachable
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json route = json::parse(r.out);
    ASSERT_TRUE(route.contains("path"));
    EXPECT_EQ(route["path"].front()["object"], 0);
    EXPECT_EQ(route["path"].back()["object"], to);
    EXPECT_GT(route["costs"]["D"].get<double>(), 0);
    EXPECT_GE(route["costs"]["U"].get<double>(), 0);
    EXPECT_GE(route["costs"]["D_over_R"].get<double>(), route["costs"]["D"].get<double>());
    EXPECT_EQ(route["custom_map"].size(), route["path"].size());
    const auto parsed = neopipe::nav::parse_custom_map(route["custom_map_text"].get<std::string>());
    EXPECT_EQ(parsed.entries.size(), route["custom_map"].size());
    ++routes;
  }
  EXPECT_GT(routes, 0);
}

// --descriptions paper keeps to Obvious and Isol; extended (the default) may describe a landmark as
// Far or Near, in the path's kinds and in a trajectory's via_description, and says which it used.
TEST_F(MapCli, DescriptionsPaperOrExtended) {
  make_world(150, 2);
  std::map<std::string, int> kinds[2];
  const std::array<std::string, 2> names{"paper", "extended"};
  for (std::size_t d = 0; d < 2; ++d) {
    for (int to = 1; to < 150; to += 9) {
      const auto r = run_neopipe({"map", "--world", file("w.yaml"), "--json", "--from", "0", "--to", std::to_string(to),
                                  "--cost", "reliability", "--sigma", "1.5", "--descriptions", names[d]});
      if (r.exit_code == 3) continue;
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const json j = json::parse(r.out);
      EXPECT_EQ(j["descriptions"], names[d]);
      for (const auto& step : j["path"]) {
        ++kinds[d][step["kind"].get<std::string>()];
        if (step.contains("via_description")) ++kinds[d]["via " + step["via_description"].get<std::string>()];
      }
      const auto parsed = neopipe::nav::parse_custom_map(j["custom_map_text"].get<std::string>());
      EXPECT_EQ(parsed.entries.size(), j["custom_map"].size());
    }
  }
  for (const char* k : {"far", "near", "via Far", "via Near"}) EXPECT_EQ(kinds[0].count(k), 0U) << k;
  EXPECT_GT(kinds[1]["far"] + kinds[1]["near"] + kinds[1]["via Far"] + kinds[1]["via Near"], 0);
  EXPECT_TRUE(
      one_error_line(run_neopipe({"map", "--world", file("w.yaml"), "--descriptions", "fancy"}), "--descriptions"));
}

TEST_F(MapCli, TextReportTableAndPlots) {
  make_world();
  RunResult r;
  for (int to = 1; to < 100; ++to) {  // the first goal reachable from object 0
    r = run_neopipe(
        {"map", "--world", file("w.yaml"), "--from", "0", "--to", std::to_string(to), "--plot", file("m.svg")});
    if (r.exit_code != 3) break;
  }
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("FROM"), std::string::npos);
  EXPECT_NE(r.out.find("custom map:"), std::string::npos);
  EXPECT_NE(r.out.find("VERIF"), std::string::npos) << r.out;
  EXPECT_NE(slurp(file("m.svg")).find("<svg"), std::string::npos);
  ASSERT_EQ(run_neopipe({"map", "--world", file("w.yaml"), "--plot", file("m.png")}).exit_code, 0);
  EXPECT_GT(fs::file_size(file("m.png")), 5000U);
}

TEST_F(MapCli, EveryCostCriterionAndTheLandmarkBasedPath) {
  // Four objects where the path of least landmark-based distance (via 1) is not the path of least
  // window travel (via 3): test_map_maker.cpp works both out by hand.
  write_text(file("four.yaml"),
             "size: [160, 160]\nobjects:\n  - [106, 29]\n  - [89, 44]\n  - [123, 89]\n  - [150, 47]\n");
  std::map<std::string, json> costs;
  for (const std::string cost : {"distance", "reliability", "ratio", "landmark"}) {
    const auto r =
        run_neopipe({"map", "--world", file("four.yaml"), "--json", "--from", "0", "--to", "2", "--cost", cost});
    ASSERT_EQ(r.exit_code, 0) << cost << ": " << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["cost"], cost);
    costs[cost] = j["costs"];
    if (cost == "landmark") {
      EXPECT_EQ(j["custom_map_text"], "((*, SE), (Obvious, (2 SE NE, ?), SW), (Obvious, (2 SE SW, ?), -))");
      EXPECT_NEAR(j["path"][1]["landmark_distance"].get<double>(), std::hypot(17, 15), 1e-9);
    }
  }
  EXPECT_LT(costs["landmark"]["landmark_distance"].get<double>(), costs["distance"]["landmark_distance"].get<double>());
  EXPECT_LT(costs["distance"]["D"].get<double>(), costs["landmark"]["D"].get<double>());
  const auto help = run_neopipe({"map", "--help"});
  EXPECT_NE(help.out.find("landmark"), std::string::npos) << help.out;
}

TEST_F(MapCli, UnreachableGoalHasItsOwnExitCode) {
  write_text(file("two.yaml"),
             "size: [600, 600]\nobjects:\n  - [50, 50]\n  - [50, 70]\n  - [400, 550]\n  - [420, 550]\n");
  const auto r = run_neopipe({"map", "--world", file("two.yaml"), "--from", "0", "--to", "2"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(one_error_line(r, "cannot be reached")) << r.err;
  EXPECT_NE(r.out.find("objects"), std::string::npos);  // the world report is still written
}

TEST_F(MapCli, BadInputIsOneLineAndNonZero) {
  make_world(20, 2);
  const std::string w = file("w.yaml");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--from", "0", "--to", "99"}), "does not exist"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--from", "5", "--to", "5"}), "same object"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--from", "5"}), "--from and --to"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--window", "800"}), "larger than"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--cost", "cheapest"}), "--cost"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--border-tolerance", "-1"}), "--border-tolerance"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", w, "--plot", file("m.gif")}), ".png or .svg"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map"}), "--world"));
  write_text(file("bad.yaml"), "size: [100, 100]\nobjects:\n  - [10, 10]\n  - [10, oops]\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", file("bad.yaml")}), ":4:")) << "line number";
  write_text(file("overlap.yaml"), "size: [100, 100]\nobjects:\n  - [10, 10]\n  - [11, 10]\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", file("overlap.yaml")}), "overlap"));
  write_text(file("empty.yaml"), "size: [100, 100]\nobjects: []\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", file("empty.yaml")}), "no objects"));
  write_text(file("one.yaml"), "size: [100, 100]\nobjects:\n  - [50, 50]\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--world", file("one.yaml")}), "one object"));
  write_text(file("blobs.csv"), "frame,blob,area,cx,cy\n0,0,10,1,2\n");
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "--blobs", file("blobs.csv")}), "no 'X' column"));
}

TEST_F(MapCli, SameWorldSameJson) {
  make_world(80, 3);
  const auto a = run_neopipe({"map", "--world", file("w.yaml"), "--json", "--from", "1", "--to", "2"});
  const auto b = run_neopipe({"map", "--world", file("w.yaml"), "--json", "--from", "1", "--to", "2"});
  EXPECT_EQ(a.exit_code, b.exit_code);
  EXPECT_EQ(a.out, b.out);
}
