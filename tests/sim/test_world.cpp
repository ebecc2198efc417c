// Worlds: random placement keeps every pair at least diameter + gap apart, inside the workspace,
// the same seed gives the same world, files read back exactly, and bad files or requests fail with
// the file, line and cause.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/world.hpp"

namespace sim = neopipe::sim;

namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

std::string load_error(const std::string& text) {
  const std::string path = temp_file("bad_world", text);
  try {
    (void)sim::load_world(path);
  } catch (const sim::WorldError& e) {
    std::filesystem::remove(path);
    return e.what();
  }
  std::filesystem::remove(path);
  return "";
}

}  // namespace

TEST(World, RandomPlacementKeepsTheGapAndTheWorkspace) {
  sim::WorldRequest q;
  q.objects = 800;
  q.min_gap = 4;
  q.seed = 3;
  const sim::World w = sim::generate_world(q);
  ASSERT_EQ(w.objects.size(), 800U);
  for (std::size_t i = 0; i < w.objects.size(); ++i) {
    EXPECT_GE(w.objects[i].x(), 2.5);
    EXPECT_LE(w.objects[i].x(), 497.5);
    EXPECT_GE(w.objects[i].y(), 2.5);
    EXPECT_LE(w.objects[i].y(), 497.5);
    for (std::size_t j = 0; j < i; ++j) ASSERT_GE((w.objects[i] - w.objects[j]).norm(), 9.0) << i << " " << j;
  }
}

TEST(World, PlacementIsUniform) {
  // Quadrant counts of 4000 marbles: each ~1000; a chi-square with 3 degrees of freedom over 16.3
  // has probability 0.001.
  sim::WorldRequest q;
  q.objects = 4000;
  q.size = {1000, 1000};
  q.min_gap = 1;
  const sim::World w = sim::generate_world(q);
  std::array<int, 4> counts{};
  for (const auto& p : w.objects) ++counts[(p.x() < 500 ? 0U : 1U) + (p.y() < 500 ? 0U : 2U)];
  double chi2 = 0;
  for (const int c : counts) chi2 += (c - 1000.0) * (c - 1000.0) / 1000.0;
  EXPECT_LT(chi2, 16.3);
}

TEST(World, SameSeedSameWorldOtherSeedOtherWorld) {
  sim::WorldRequest q;
  q.objects = 200;
  const auto a = sim::generate_world(q);
  const auto b = sim::generate_world(q);
  q.seed = 2;
  const auto c = sim::generate_world(q);
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) EXPECT_EQ(a.objects[i], b.objects[i]);
  EXPECT_NE(a.objects[0], c.objects[0]);
}

TEST(World, FileReadsBackExactly) {
  sim::WorldRequest q;
  q.objects = 300;
  q.size = {320.5, 240};
  q.marble_diameter = 4.25;
  const auto w = sim::generate_world(q);
  const std::string path = temp_file("roundtrip", "");
  sim::save_world(w, path);
  const auto r = sim::load_world(path);
  std::filesystem::remove(path);
  EXPECT_EQ(r.size, w.size);
  EXPECT_EQ(r.marble_diameter, w.marble_diameter);
  ASSERT_EQ(r.objects.size(), w.objects.size());
  for (std::size_t i = 0; i < w.objects.size(); ++i) EXPECT_EQ(r.objects[i], w.objects[i]);
}

TEST(World, TheIssuesExampleLoads) {
  const std::string path =
      temp_file("example", "size: [500, 500]\nobjects:\n  - [118.982, 272.115]\n  - [184.978, 301.96]\n");
  const auto w = sim::load_world(path);
  std::filesystem::remove(path);
  EXPECT_EQ(w.objects.size(), 2U);
  EXPECT_EQ(w.objects[1].y(), 301.96);
  EXPECT_EQ(w.marble_diameter, 5.0);
}

TEST(World, BadFilesNameTheLineAndTheCause) {
  EXPECT_NE(
      load_error("size: [500, 500]\nobjects:\n  - [10, 10]\n  - [12, 10]\n").find(":4:5: object 1 overlaps object 0"),
      std::string::npos);
  EXPECT_NE(load_error("size: [500, 500]\nobjects:\n  - [10, 10]\n  - [600, 10]\n")
                .find(":4:5: object 1 at (600, 10) is not wholly on"),
            std::string::npos);
  EXPECT_NE(load_error("size: [500, 500]\nobjects:\n  - [10, ten]\n").find(":3:10: object 0: 'ten' is not a number"),
            std::string::npos);
  EXPECT_NE(load_error("size: [500]\nobjects: []\n").find(":1:7: size must be a pair"), std::string::npos);
  EXPECT_NE(load_error("objects: []\n").find("missing 'size'"), std::string::npos);
  EXPECT_NE(load_error("size: [5, 5]\nobject: []\n").find(":2:1: unknown key 'object'"), std::string::npos);
  EXPECT_NE(load_error("size: [5, 5\nobjects: []\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(load_error("size: [500, 500]\nmarble_diameter: -1\nobjects: []\n")
                .find(":2:18: 'marble_diameter' must be positive"),
            std::string::npos);
  EXPECT_THROW((void)sim::load_world("/nonexistent/world.yaml"), sim::WorldError);
}

TEST(World, ImpossibleRequestsAreRefused) {
  sim::WorldRequest q;
  q.objects = 5000;
  q.size = {100, 100};
  try {
    (void)sim::generate_world(q);
    FAIL() << "5000 marbles fit in 100 x 100 mm?";
  } catch (const sim::WorldError& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit"), std::string::npos) << e.what();
  }
  q.objects = 10;
  q.size = {4, 100};
  EXPECT_THROW((void)sim::generate_world(q), sim::WorldError);
  q.size = {100, 100};
  q.min_gap = -1;
  EXPECT_THROW((void)sim::generate_world(q), sim::WorldError);
}
