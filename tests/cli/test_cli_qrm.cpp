// `neopipe qrm`: the tables as JSON against the library, the table file checks, and the true RNG of
// a world with its bad inputs.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_test_support.hpp"
#include "nav/qrm/composition.hpp"
#include "nav/qrm/operators.hpp"

namespace {
namespace fs = std::filesystem;
namespace qrm = neopipe::nav::qrm;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

class QrmCli : public ScratchDirTest {};

qrm::StateSet set_of(const json& list) {
  qrm::StateSet s;
  int previous = 0;
  for (const auto& v : list) {
    const int state = v.get<int>();
    EXPECT_GT(state, previous) << "sorted, no repeats";
    previous = state;
    s.insert(state);
  }
  return s;
}

// The spec's navigation example (qrm.md §8), scaled by 10 and moved into a 500 x 500 workspace.
const char* kExampleWorld =
    "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [140, 105]\n  - [115, 112]\n  - [190, 90]\n  - [160, 143]\n";

}  // namespace

TEST_F(QrmCli, TablesJsonAgreesWithTheLibrary) {
  const auto r = run_neopipe({"qrm", "tables", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["compose"].size(), 20U);
  int triples = 0;
  for (qrm::State s = 1; s <= qrm::kStateCount; ++s) {
    const std::string key = std::to_string(s);
    EXPECT_EQ(set_of(j["left"][key]), qrm::left_shift(s));
    EXPECT_EQ(set_of(j["right"][key]), qrm::right_shift(s));
    EXPECT_EQ(set_of(j["inverse"][key]), qrm::StateSet{qrm::inverse(s)});
    ASSERT_EQ(j["compose"][s - 1].size(), 20U);
    for (qrm::State t = 1; t <= qrm::kStateCount; ++t) {
      const qrm::StateSet entry = set_of(j["compose"][s - 1][t - 1]);
      EXPECT_EQ(entry, qrm::composition_table()(s, t));
      triples += entry.count();
    }
  }
  EXPECT_EQ(triples, 2214);
  EXPECT_EQ(j["left"]["1"], json::parse("[17]"));
  EXPECT_EQ(j["compose"][0][0], json::parse("[1,5,11,19]"));
  // The text form prints the same tables.
  const auto text = run_neopipe({"qrm", "tables"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("  7  {1,5}    {12,17}   14"), std::string::npos) << text.out.substr(0, 600);
  EXPECT_NE(text.out.find("  1  17  {5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20}"), std::string::npos);
}

TEST_F(QrmCli, CheckAcceptsTheCommittedTableAndNamesACorruptOne) {
  const std::string committed = std::string(NEOPIPE_SOURCE_DIR) + "/nav/qrm/composition_table.txt";
  const auto ok = run_neopipe({"qrm", "tables", "--check", committed});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("identical to the built-in table (2214 feasible triples)"), std::string::npos);

  std::string text = slurp(committed);
  text.replace(text.find("\n1 1 1,5,11,19\n"), 15, "\n1 1 1,5,11,18\n");
  write_text(file("corrupt.txt"), text);
  const auto corrupt = run_neopipe({"qrm", "tables", "--check", file("corrupt.txt")});
  EXPECT_TRUE(one_error_line(corrupt, file("corrupt.txt") + ": line 407: checksum mismatch")) << corrupt.err;

  write_text(file("old.txt"), "neopipe-qrm-composition 0 box 8 depth 40\n");
  const auto old = run_neopipe({"qrm", "tables", "--check", file("old.txt")});
  EXPECT_TRUE(one_error_line(old, "format version 0")) << old.err;

  const auto missing = run_neopipe({"qrm", "tables", "--check", file("none.txt")});
  EXPECT_TRUE(one_error_line(missing, file("none.txt") + ": cannot open")) << missing.err;

  const auto sample = run_neopipe({"qrm", "tables", "--sample", "200000", "--seed", "3"});
  ASSERT_EQ(sample.exit_code, 0) << sample.err;
  EXPECT_NE(sample.out.find(": 0 outside the built-in table"), std::string::npos) << sample.out;
}

TEST_F(QrmCli, RngOfTheNavigationExample) {
  write_text(file("w.yaml"), kExampleWorld);
  const auto r = run_neopipe({"qrm", "rng", "--world", file("w.yaml"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out), json::parse(R"({"edges": [[0, 2], [1, 2], [1, 3], [1, 4]]})"));
  const auto text = run_neopipe({"qrm", "rng", "--world", file("w.yaml")});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_EQ(text.out, "5 marbles, 4 RNG edges (i j):\n0 2\n1 2\n1 3\n1 4\n");
}

TEST_F(QrmCli, RngOfAGeneratedWorldHasEveryMarble) {
  const auto w = run_neopipe({"sim", "world", "--objects", "40", "--seed", "4", "--out", file("w.yaml")});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto r = run_neopipe({"qrm", "rng", "--world", file("w.yaml"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json edges = json::parse(r.out)["edges"];
  // The RNG is connected and contains the Euclidean minimum spanning tree: at least n - 1 edges,
  // and planar: at most 3n - 6.
  EXPECT_GE(edges.size(), 39U);
  EXPECT_LE(edges.size(), 3U * 40 - 6);
  std::vector<bool> touched(40, false);
  for (const auto& e : edges) {
    EXPECT_LT(e[0].get<int>(), e[1].get<int>());
    touched[e[0].get<int>()] = touched[e[1].get<int>()] = true;
  }
  for (int i = 0; i < 40; ++i) EXPECT_TRUE(touched[i]) << i;
}

TEST_F(QrmCli, BadWorldsAreOneLineErrors) {
  write_text(file("two.yaml"), "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [200, 200]\n");
  const auto two = run_neopipe({"qrm", "rng", "--world", file("two.yaml")});
  EXPECT_TRUE(one_error_line(two, file("two.yaml") + ": 2 marbles; the RNG through the EDC needs at least 3"))
      << two.err;
  write_text(file("line.yaml"),
             "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [150, 100]\n  - [300, 100]\n"
             "  - [120, 200]\n");
  const auto line = run_neopipe({"qrm", "rng", "--world", file("line.yaml"), "--json"});
  EXPECT_TRUE(one_error_line(line, file("line.yaml") + ": landmarks 0, 1 and 2 form a degenerate triple")) << line.err;
  EXPECT_TRUE(line.out.empty());
  const auto missing = run_neopipe({"qrm", "rng", "--world", file("none.yaml")});
  EXPECT_TRUE(one_error_line(missing, file("none.yaml"))) << missing.err;
  const auto no_world = run_neopipe({"qrm", "rng"});
  EXPECT_EQ(no_world.exit_code, 2);
  const auto help = run_neopipe({"qrm", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("tables"), std::string::npos);
}

namespace {

std::vector<std::pair<int, int>> edge_list(const json& list) {
  std::vector<std::pair<int, int>> edges;
  for (const auto& e : list) {
    EXPECT_EQ(e.size(), 2U);
    edges.emplace_back(e[0].get<int>(), e[1].get<int>());
    EXPECT_LT(edges.back().first, edges.back().second);
  }
  EXPECT_TRUE(std::is_sorted(edges.begin(), edges.end()));
  return edges;
}

}  // namespace

TEST_F(QrmCli, BuildFindsTheTrueRngOfASmallWorld) {
  const auto w =
      run_neopipe({"sim", "world", "--objects", "6", "--size", "200x200", "--seed", "1", "--out", file("w.yaml")});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto r = run_neopipe({"qrm", "build", "--world", file("w.yaml"), "--images", "20", "--k", "6", "--seed", "2",
                              "--json", "--plot", file("b.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  for (const char* m : {"m1", "m2", "m3", "m4", "m5_us", "triples", "inconsistent"}) {
    ASSERT_EQ(j["per_image"][m].size(), 20U) << m;
  }
  // M1 never falls: states once removed stay removed.
  double previous = 0;
  for (const auto& m1 : j["per_image"]["m1"]) {
    EXPECT_GE(m1.get<double>(), previous);
    previous = m1.get<double>();
  }
  EXPECT_EQ(j["per_image"]["triples"][0].get<int>(), 20);  // C(6, 3)
  EXPECT_GT(j["final"]["m1"].get<double>(), 90);
  EXPECT_EQ(j["final"]["lost_true_states"].get<int>(), 0);
  EXPECT_EQ(j["inconsistencies"].get<int>(), 0);
  const auto truth = edge_list(j["true_rng"]);
  EXPECT_GE(truth.size(), 5U);  // the RNG is connected
  EXPECT_EQ(edge_list(j["rng"]), truth);
  EXPECT_EQ(edge_list(j["certain_rng"]), truth);
  EXPECT_TRUE(j["final"]["rng_equal"].get<bool>());
  // The same as `neopipe qrm rng` says.
  const auto rng = run_neopipe({"qrm", "rng", "--world", file("w.yaml"), "--json"});
  EXPECT_EQ(json::parse(rng.out)["edges"], j["true_rng"]);
  EXPECT_GT(fs::file_size(file("b.png")), 1000U);
  // Deterministic for a seed; the text form reports the same final line.
  const auto again =
      run_neopipe({"qrm", "build", "--world", file("w.yaml"), "--images", "20", "--k", "6", "--seed", "2", "--json"});
  EXPECT_EQ(json::parse(again.out)["per_image"]["m1"], j["per_image"]["m1"]);
  const auto text = run_neopipe({"qrm", "build", "--world", file("w.yaml"), "--images", "3", "--k", "6"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("final: M1"), std::string::npos) << text.out;
}

TEST_F(QrmCli, BuildRejectsBadInputsInOneLine) {
  write_text(file("two.yaml"), "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [200, 200]\n");
  const auto two = run_neopipe({"qrm", "build", "--world", file("two.yaml")});
  EXPECT_TRUE(one_error_line(two, file("two.yaml") + ": 2 marbles; a relational map needs at least 3")) << two.err;
  write_text(file("line.yaml"),
             "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [150, 100]\n  - [300, 100]\n  - [120, 200]\n");
  const auto line = run_neopipe({"qrm", "build", "--world", file("line.yaml"), "--json"});
  EXPECT_TRUE(one_error_line(line, file("line.yaml") + ": landmarks 0, 1 and 2 form a degenerate triple")) << line.err;
  EXPECT_TRUE(line.out.empty());
  write_text(file("w.yaml"), "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [140, 105]\n  - [115, 112]\n");
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{"--k", "2"}, {"--images", "0"}, {"--noise", "-1"}, {"--k", "x"}}) {
    std::vector<std::string> args{"qrm", "build", "--world", file("w.yaml")};
    args.insert(args.end(), bad.begin(), bad.end());
    const auto r = run_neopipe(args);
    EXPECT_EQ(r.exit_code, 2) << bad[0] << " " << bad[1] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const auto missing = run_neopipe({"qrm", "build", "--world", file("none.yaml")});
  EXPECT_TRUE(one_error_line(missing, file("none.yaml"))) << missing.err;
  const auto help = run_neopipe({"qrm", "build", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--images"), std::string::npos);
  const auto bad_list = run_neopipe({"qrm", "experiment", "--k", "6,x", "--out", file("e")});
  EXPECT_EQ(bad_list.exit_code, 2) << bad_list.err;
}

TEST_F(QrmCli, ExperimentWritesOneRowPerRunKAndImage) {
  const auto r = run_neopipe(
      {"qrm", "experiment", "--runs", "3", "--images", "4", "--k", "6,9", "--marbles", "12", "--out", file("e")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(file("e") + "/qrm_runs.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("marbles,run,k,image,m1,m2,m3,m4,m5_us", 0), 0U) << header;
  int rows = 0;
  for (std::string row; std::getline(in, row);) ++rows;
  EXPECT_EQ(rows, 3 * 2 * 4);
}
