// The moves file: good lines with their line numbers (blank lines, spaces, CRLF, a byte order mark
// and a leading '+' accepted), and every kind of bad file reported as "<path>[:<line>]: <cause>".

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sim/arm/moves_csv.hpp"

namespace neopipe::sim {
namespace {

namespace fs = std::filesystem;

class MovesCsv : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("neopipe_arm_moves_" + std::to_string(getpid()) + "_" +
                                        testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& text) const {
    const fs::path p = dir_ / "moves.csv";
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }

  /// The message reading `text` fails with, after the good lines before it.
  std::string error_of(const std::string& text) const {
    const std::string path = write(text);
    try {
      MovesReader reader(path);
      while (reader.next()) {
      }
    } catch (const MovesError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(path, 0), 0U) << m;  // starts with the path
      return m.substr(path.size());
    }
    ADD_FAILURE() << "accepted: " << text;
    return {};
  }

  fs::path dir_;
};

TEST_F(MovesCsv, ReadsEveryMoveWithItsLineNumber) {
  MovesReader reader(
      write("\xEF\xBB\xBF"
            "dx, dy ,dtheta\r\n100,0,0\r\n\r\n  -20.5 , +3e1,90\n0,0,-45.25"));
  std::vector<MoveLine> moves;
  while (const auto m = reader.next()) moves.push_back(*m);
  ASSERT_EQ(moves.size(), 3U);
  EXPECT_EQ(moves[0].line, 2);
  EXPECT_EQ(moves[0].dx, 100);
  EXPECT_EQ(moves[1].line, 4);
  EXPECT_EQ(moves[1].dx, -20.5);
  EXPECT_EQ(moves[1].dy, 30);
  EXPECT_EQ(moves[1].dtheta_deg, 90);
  EXPECT_EQ(moves[2].line, 5);
  EXPECT_EQ(moves[2].dtheta_deg, -45.25);
  EXPECT_FALSE(reader.next());
}

TEST_F(MovesCsv, AHeaderAloneIsNoMoves) {
  MovesReader reader(write("dx,dy,dtheta\n"));
  EXPECT_FALSE(reader.next());
}

TEST_F(MovesCsv, MissingEmptyAndDirectoryFilesAreNamed) {
  EXPECT_EQ(error_of(""), ": empty; the first line must be the header dx,dy,dtheta");
  try {
    MovesReader reader((dir_ / "nothing.csv").string());
    ADD_FAILURE() << "a missing file was opened";
  } catch (const MovesError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "nothing.csv").string() + ": no such file");
  }
  EXPECT_THROW(MovesReader reader(dir_.string()), MovesError);
}

TEST_F(MovesCsv, AWrongHeaderIsLineOne) {
  EXPECT_EQ(error_of("x,y,theta\n1,2,3\n"), ":1: the header must be 'dx,dy,dtheta' (mm, mm, degrees), not 'x,y,theta'");
  EXPECT_EQ(error_of("1,2,3\n"), ":1: the header must be 'dx,dy,dtheta' (mm, mm, degrees), not '1,2,3'");
  EXPECT_EQ(error_of("dx,dy\n"), ":1: the header must be 'dx,dy,dtheta' (mm, mm, degrees), not 'dx,dy'");
}

TEST_F(MovesCsv, BadLinesAreNamedByNumberAfterTheGoodOnes) {
  EXPECT_EQ(error_of("dx,dy,dtheta\n1,2,3\n1,2\n"), ":3: expected 3 fields dx,dy,dtheta, found 2");
  EXPECT_EQ(error_of("dx,dy,dtheta\n1,2,3,4\n"), ":2: expected 3 fields dx,dy,dtheta, found 4");
  EXPECT_EQ(error_of("dx,dy,dtheta\n\n1,abc,3\n"), ":3: dy 'abc' is not a number");
  EXPECT_EQ(error_of("dx,dy,dtheta\n1,2,\n"), ":2: dtheta '' is not a number");
  EXPECT_EQ(error_of("dx,dy,dtheta\n1.5.2,2,3\n"), ":2: dx '1.5.2' is not a number");
  EXPECT_EQ(error_of("dx,dy,dtheta\n1,2,3 deg\n"), ":2: dtheta '3 deg' is not a number");
  EXPECT_EQ(error_of("dx,dy,dtheta\ninf,2,3\n"), ":2: dx 'inf' is not a finite number");
  EXPECT_EQ(error_of("dx,dy,dtheta\n1,nan,3\n"), ":2: dy 'nan' is not a finite number");
}

}  // namespace
}  // namespace neopipe::sim
