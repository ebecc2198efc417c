// `neopipe qualnav`: the orientation regions of a world as JSON (keys, counts against the formula),
// a subset of marbles, the plots, the productions table against the library, and bad inputs as
// one-line errors naming them.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "nav/qualnav/topology/productions.hpp"

namespace {
namespace qn = neopipe::nav::qualnav;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using nlohmann::json;

class QualnavCli : public ScratchDirTest {};

// A square's corners (0..3) and a fifth marble off every line of theirs.
const char* kSquareWorld =
    "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [300, 100]\n  - [300, 300]\n  - [100, 300]\n"
    "  - [420, 170]\n";

}  // namespace

TEST_F(QualnavCli, RegionsJsonOfARandomWorld) {
  const auto w = run_neopipe({"sim", "world", "--objects", "7", "--seed", "3", "--out", file("w7.yaml")});
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const auto r = run_neopipe({"qualnav", "regions", "--world", file("w7.yaml"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  for (const char* key : {"landmarks", "ids", "lines", "regions", "crossings"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["landmarks"], 7);
  EXPECT_EQ(j["lines"], 21);
  EXPECT_EQ(j["regions"], 162);  // the paper's count for seven landmarks in general position
  // R = 1 + N + Σ(m_p − 1) from the crossings listed; 7 landmarks and 3·C(7,4) = 105 other crossings.
  std::size_t r_count = 1 + j["lines"].get<std::size_t>();
  std::size_t at_landmarks = 0;
  for (const json& c : j["crossings"]) {
    for (const char* key : {"x", "y", "multiplicity", "landmark", "lines"}) ASSERT_TRUE(c.contains(key)) << key;
    EXPECT_EQ(c["lines"].size(), c["multiplicity"].get<std::size_t>());
    r_count += c["multiplicity"].get<std::size_t>() - 1;
    at_landmarks += c["landmark"].is_null() ? 0 : 1;
  }
  EXPECT_EQ(r_count, 162U);
  EXPECT_EQ(at_landmarks, 7U);
  EXPECT_EQ(j["crossings"].size(), 7U + 105U);
  const auto text = run_neopipe({"qualnav", "regions", "--world", file("w7.yaml")});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("7 landmarks, 21 LPB lines, 162 orientation regions"), std::string::npos) << text.out;
}

TEST_F(QualnavCli, RegionsOfChosenLandmarksAndTheirPlots) {
  write_text(file("square.yaml"), kSquareWorld);
  const auto r = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--landmarks", "0,1,2,3", "--json",
                              "--plot", file("square.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["landmarks"], 4);
  EXPECT_EQ(j["ids"], json::parse("[0,1,2,3]"));
  EXPECT_EQ(j["regions"], 16);           // the spec's square
  EXPECT_EQ(j["crossings"].size(), 5U);  // four corners and the centre; the sides are parallel
  EXPECT_GT(fs::file_size(file("square.png")), 1000U);
  const auto svg = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--plot", file("all.svg")});
  ASSERT_EQ(svg.exit_code, 0) << svg.err;
  EXPECT_NE(slurp(file("all.svg")).find("<svg"), std::string::npos);
  const auto bad_plot = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--plot", file("x.gif")});
  EXPECT_TRUE(one_error_line(bad_plot, "x.gif: the picture must be a .png or .svg file")) << bad_plot.err;
  EXPECT_EQ(bad_plot.exit_code, 2);
}

TEST_F(QualnavCli, ProductionsAgreeWithTheLibrary) {
  const auto r = run_neopipe({"qualnav", "productions", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["orders"], json::parse(R"(["ABCD","ACBD","ACDB","CABD","CDAB","CADB"])"));
  const auto table = qn::production_table();
  ASSERT_EQ(j["cells"].size(), 96U);
  for (std::size_t i = 0; i < table.size(); ++i) {
    const json& c = j["cells"][i];
    EXPECT_EQ(c["x"], std::string{qn::specifier_letter(table[i].x)});
    EXPECT_EQ(c["y"], std::string{qn::specifier_letter(table[i].y)});
    EXPECT_EQ(c["order"], table[i].order);
    EXPECT_EQ(c["production"], table[i].production);
  }
  // Two cells of the spec's table, read off by hand: l/l CABD and l/a CDAB.
  EXPECT_EQ(j["cells"][5 * 6 + 3]["production"], "l[CA]");
  EXPECT_EQ(j["cells"][7 * 6 + 4]["production"], "a[CC]");
  const auto text = run_neopipe({"qualnav", "productions"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("b    b    –      b[CB]  b[CD]  b[AB]  –      b[AD]"), std::string::npos) << text.out;
}

TEST_F(QualnavCli, BadInputsAreOneLineErrorsNamingThem) {
  write_text(file("square.yaml"), kSquareWorld);
  const auto one = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--landmarks", "2"});
  EXPECT_TRUE(one_error_line(one, file("square.yaml") + ": orientation regions need at least two landmarks, got 1"))
      << one.err;
  write_text(file("lonely.yaml"), "size: [500, 500]\nobjects:\n  - [100, 100]\n");
  const auto lonely = run_neopipe({"qualnav", "regions", "--world", file("lonely.yaml")});
  EXPECT_TRUE(one_error_line(lonely, "at least two landmarks, got 1")) << lonely.err;
  write_text(file("line.yaml"),
             "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [150, 100]\n  - [120, 200]\n  - [300, 100]\n");
  const auto line = run_neopipe({"qualnav", "regions", "--world", file("line.yaml"), "--json"});
  EXPECT_TRUE(one_error_line(line, file("line.yaml") +
                                       ": orientation regions: landmarks 0, 1 and 3 are collinear, so their LPB "
                                       "lines coincide"))
      << line.err;
  EXPECT_TRUE(line.out.empty());
  // Without marble 3 the others are in general position.
  const auto fine = run_neopipe({"qualnav", "regions", "--world", file("line.yaml"), "--landmarks", "0,1,2", "--json"});
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_EQ(json::parse(fine.out)["regions"], 7);
  const auto unknown = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--landmarks", "0,9"});
  EXPECT_TRUE(one_error_line(unknown, "--landmarks 0,9: " + file("square.yaml") +
                                          " has 5 marbles (ids 0 to 4), no "
                                          "marble 9"))
      << unknown.err;
  const auto twice = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--landmarks", "1,1"});
  EXPECT_TRUE(one_error_line(twice, "--landmarks 1,1: marble 1 is given twice")) << twice.err;
  const auto syntax = run_neopipe({"qualnav", "regions", "--world", file("square.yaml"), "--landmarks", "1,x"});
  EXPECT_TRUE(one_error_line(syntax, "--landmarks 1,x: expected a comma-separated list of marble ids")) << syntax.err;
  EXPECT_EQ(syntax.exit_code, 2);
  // Coincident marbles cannot come from a world file: the world's own check names them.
  write_text(file("same.yaml"), "size: [500, 500]\nobjects:\n  - [100, 100]\n  - [100, 100]\n  - [200, 300]\n");
  const auto same = run_neopipe({"qualnav", "regions", "--world", file("same.yaml")});
  EXPECT_TRUE(one_error_line(same, file("same.yaml"))) << same.err;
  write_text(file("broken.yaml"), "size: [500, 500]\nobjects: [[1, 2\n");
  const auto broken = run_neopipe({"qualnav", "regions", "--world", file("broken.yaml")});
  EXPECT_TRUE(one_error_line(broken, file("broken.yaml"))) << broken.err;
  const auto missing = run_neopipe({"qualnav", "regions", "--world", file("none.yaml")});
  EXPECT_TRUE(one_error_line(missing, file("none.yaml"))) << missing.err;
  const auto no_world = run_neopipe({"qualnav", "regions"});
  EXPECT_EQ(no_world.exit_code, 2);
  const auto help = run_neopipe({"qualnav", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("productions"), std::string::npos);
}
