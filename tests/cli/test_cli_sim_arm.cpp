// End-to-end tests of `neopipe sim arm`: the built binary runs as a child process on world and moves
// files written here. Checked: the report's header and rows (exact poses without errors, the start
// as row 0), determinism by seed, --out vs stdout, the stderr summary, the error options, and bad
// input (missing files, malformed CSV, unreachable moves and starts, bad option values): a non-zero
// exit, exactly one "neopipe sim arm: error: <file>:<line>: <cause>" line, rows already made kept.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace {
namespace fs = std::filesystem;

using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)
using Outcome = RunResult;
const std::string kError = "neopipe sim arm: error: ";
// Errors CLI11 finds while parsing name the whole subcommand too.
const std::string kParseError = "neopipe sim arm: error: ";
const std::string kReportHeader =
    "move,dx,dy,dtheta,cmd_x,cmd_y,cmd_theta,x,y,theta,err_x,err_y,err_theta,shoulder,elbow,roll";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& row) {
  std::vector<std::string> fields;
  std::istringstream in(row);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

class CliSimArm : public testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("neopipe_cli_sim_arm_" + std::to_string(getpid()) + "_" +
                                       testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    world = (dir / "world.yaml").string();
    write_text(world, "size: [500, 500]\nmarble_diameter: 5\nobjects:\n  - [100, 100]\n  - [400, 300]\n");
  }
  void TearDown() override {
    if (std::getenv("NEOPIPE_CLI_KEEP_TMP") == nullptr) fs::remove_all(dir);
  }

  std::string moves_file(const std::string& text, const std::string& name = "moves.csv") const {
    write_text(dir / name, text);
    return (dir / name).string();
  }
  Outcome arm(std::vector<std::string> args) const {
    args.insert(args.begin(), {"sim", "arm"});
    return run_neopipe(args);
  }
  /// Checks a failed run: the exit code, and stderr is one line starting with `start` and containing
  /// each of `needles`.
  void expect_error(const Outcome& r, int code, const std::string& start,
                    const std::vector<std::string>& needles) const {
    EXPECT_FALSE(r.signaled);
    EXPECT_EQ(r.exit_code, code) << r.err;
    const auto lines = lines_of(r.err);
    ASSERT_EQ(lines.size(), 1U) << r.err;
    EXPECT_EQ(lines[0].rfind(start, 0), 0U) << lines[0];
    for (const auto& n : needles) EXPECT_TRUE(contains(lines[0], n)) << "lacks '" << n << "': " << lines[0];
  }

  fs::path dir;
  std::string world;
};

TEST_F(CliSimArm, WithoutErrorsTheReportHoldsTheExactCommandedPoses) {
  const std::string moves = moves_file("dx,dy,dtheta\n100,0,90\n100,0,0\n0,-50,-90\n");
  const fs::path out = dir / "report.csv";
  const Outcome r = arm({"--world", world, "--moves", moves, "--no-errors", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  const auto rows = lines_of(slurp(out));
  ASSERT_EQ(rows.size(), 5U);
  EXPECT_EQ(rows[0], kReportHeader);
  // From the centre, heading East: 100 mm East and turn left; 100 mm North; 50 mm right (East), turn back.
  const std::vector<std::vector<std::string>> expected_xy_theta{{"250.000000", "250.000000", "0.000000"},
                                                                {"350.000000", "250.000000", "90.000000"},
                                                                {"350.000000", "350.000000", "90.000000"},
                                                                {"400.000000", "350.000000", "0.000000"}};
  for (std::size_t i = 0; i < expected_xy_theta.size(); ++i) {
    const auto f = fields_of(rows[i + 1]);
    ASSERT_EQ(f.size(), 16U) << rows[i + 1];
    EXPECT_EQ(f[0], std::to_string(i));
    EXPECT_EQ(std::vector<std::string>(f.begin() + 4, f.begin() + 7), expected_xy_theta[i]) << rows[i + 1];   // cmd
    EXPECT_EQ(std::vector<std::string>(f.begin() + 7, f.begin() + 10), expected_xy_theta[i]) << rows[i + 1];  // truth
    EXPECT_EQ(std::vector<std::string>(f.begin() + 10, f.begin() + 13),
              (std::vector<std::string>{"0.000000", "0.000000", "0.000000"}))
        << rows[i + 1];
  }
  EXPECT_TRUE(contains(r.err, "3 moves (seed 1)")) << r.err;
  EXPECT_TRUE(contains(r.err, "error 0.000 mm, 0.000 deg")) << r.err;
}

TEST_F(CliSimArm, ErrorsDependOnTheSeedOnly) {
  std::string text = "dx,dy,dtheta\n";
  for (int i = 0; i < 20; ++i) text += (i % 2 ? "-30,10,5\n" : "40,-5,-3\n");
  const std::string moves = moves_file(text);
  const Outcome a = arm({"--world", world, "--moves", moves, "--seed", "7"});
  const Outcome b = arm({"--world", world, "--moves", moves, "--seed", "7"});
  const Outcome c = arm({"--world", world, "--moves", moves, "--seed", "8"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(lines_of(a.out).size(), 22U);
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
  const auto last = fields_of(lines_of(a.out).back());
  EXPECT_NE(last[10], "0.000000");  // the default errors are on
  EXPECT_NE(last[12], "0.000000");
}

TEST_F(CliSimArm, ErrorOptionsSetTheSigmas) {
  // Only a heading error: every position error comes from the drifting tool frame, none at move 1.
  const std::string moves = moves_file("dx,dy,dtheta\n0,0,0\n100,0,0\n");
  const Outcome r = arm({"--world", world, "--moves", moves, "--sigma0", "0", "--along-per-mm", "0", "--across-per-mm",
                         "0", "--rot-sigma0", "1", "--rot-per-mm", "0", "--rot-per-deg", "0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = lines_of(r.out);
  ASSERT_EQ(rows.size(), 4U);
  const auto first = fields_of(rows[2]);
  EXPECT_EQ(first[10], "0.000000");
  EXPECT_EQ(first[11], "0.000000");
  EXPECT_NE(first[12], "0.000000");
  EXPECT_NE(fields_of(rows[3])[11], "0.000000");
}

TEST_F(CliSimArm, StartBaseAndLinksAreHonoured) {
  const std::string moves = moves_file("dx,dy,dtheta\n");
  const Outcome r = arm({"--world", world, "--moves", moves, "--no-errors", "--start", "100,-20,45", "--base",
                         "250,-200", "--links", "400,380"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto f = fields_of(lines_of(r.out).at(1));
  EXPECT_EQ(std::vector<std::string>(f.begin() + 7, f.begin() + 10),
            (std::vector<std::string>{"100.000000", "-20.000000", "45.000000"}));
  EXPECT_TRUE(contains(r.err, "base (250, -200) mm, links 400 + 380 mm")) << r.err;
}

TEST_F(CliSimArm, AnUnreachableMoveStopsTheRunAfterTheRowsBeforeIt) {
  const std::string moves = moves_file("dx,dy,dtheta\n10,0,0\n10,0,0\n1000,0,0\n10,0,0\n");
  const fs::path out = dir / "report.csv";
  const Outcome r = arm({"--world", world, "--moves", moves, "--out", out.string()});
  expect_error(r, 1, kError + moves + ":4: move (1000.00, 0.00, 0.00 deg) from (",
               {"mm from the base (250.00, -125.00); the arm reaches 65.37..749.97 mm"});
  const auto rows = lines_of(slurp(out));
  ASSERT_EQ(rows.size(), 4U);  // header, start, moves 1 and 2
  EXPECT_EQ(fields_of(rows.back())[0], "2");
}

TEST_F(CliSimArm, MalformedMovesAreNamedByLineAfterTheRowsBeforeThem) {
  const fs::path out = dir / "report.csv";
  struct Case {
    std::string text;
    std::string error;
    std::size_t rows;
  } const cases[] = {
      {"dx,dy,dtheta\n1,2,3\n1,2\n", ":3: expected 3 fields dx,dy,dtheta, found 2", 3},
      {"dx,dy,dtheta\n1,abc,3\n", ":2: dy 'abc' is not a number", 2},
      {"dx,dy,dtheta\n1,2,3\n\n4,5,nan\n", ":4: dtheta 'nan' is not a finite number", 3},
      {"x,y,theta\n1,2,3\n", ":1: the header must be 'dx,dy,dtheta'", 0},
      {"", ": empty; the first line must be the header dx,dy,dtheta", 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    fs::remove(out);
    const std::string moves = moves_file(c.text);
    const Outcome r = arm({"--world", world, "--moves", moves, "--out", out.string()});
    expect_error(r, 1, kError + moves + c.error, {});
    EXPECT_EQ(lines_of(slurp(out)).size(), c.rows);  // no report at all when the header is bad
  }
}

TEST_F(CliSimArm, MissingFilesAreErrors) {
  const std::string moves = moves_file("dx,dy,dtheta\n1,2,3\n");
  expect_error(arm({"--world", (dir / "none.yaml").string(), "--moves", moves}), 1,
               kError + (dir / "none.yaml").string(), {"no such file"});
  expect_error(arm({"--world", world, "--moves", (dir / "none.csv").string()}), 1, kError + (dir / "none.csv").string(),
               {"no such file"});
}

TEST_F(CliSimArm, AnUnreachableStartIsAnError) {
  const std::string moves = moves_file("dx,dy,dtheta\n");
  expect_error(arm({"--world", world, "--moves", moves, "--start", "250,700,0"}), 1, kError + "--start 250,700,0: pose",
               {"825.00 mm from the base"});
}

TEST_F(CliSimArm, BadOptionValuesAreUsageErrors) {
  const std::string moves = moves_file("dx,dy,dtheta\n");
  expect_error(arm({"--world", world, "--moves", moves, "--start", "250,250"}), 2,
               kError + "--start 250,250: expected X,Y,THETA", {});
  expect_error(arm({"--world", world, "--moves", moves, "--base", "a,b"}), 2, kError + "--base a,b: expected X,Y", {});
  expect_error(arm({"--world", world, "--moves", moves, "--links", "1,2,"}), 2, kError + "--links 1,2,: expected L1,L2",
               {});
  expect_error(arm({"--world", world, "--moves", moves, "--sigma0", "-1"}), 2, kParseError, {"--sigma0"});
  expect_error(arm({"--world", world, "--moves", moves, "--no-errors", "--sigma0", "1"}), 2, kParseError, {"excludes"});
  expect_error(arm({"--world", world}), 2, kParseError, {"--moves"});
  expect_error(arm({"--world", world, "--moves", moves, "--links", "0,300"}), 1, kError + "link lengths", {});
}

TEST_F(CliSimArm, HelpDescribesTheFormatsAndOptions) {
  const Outcome r = arm({"--help"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string m : {"--world", "--moves", "--out", "--seed", "--start", "--base", "--links", "--sigma0",
                              "--along-per-mm", "--across-per-mm", "--rot-sigma0", "--rot-per-mm", "--rot-per-deg",
                              "--no-errors", "dx,dy,dtheta", "degrees", kReportHeader.c_str(), "Exit status"}) {
    EXPECT_TRUE(contains(r.out, m)) << "help lacks " << m << ":\n" << r.out;
  }
}

}  // namespace
