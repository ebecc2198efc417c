// Worlds: random placement keeps every pair at least diameter + gap apart, inside the workspace,
// spreads centres uniformly (Kolmogorov-Smirnov on x and y, chi-square on a 10 x 10 grid, both
// shown to catch a 10% squeeze towards the centre), the same seed gives the same world, files read back exactly, and
// bad files or requests fail with the file, line and cause.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

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

namespace {

// Uniformity statistics of marble centres over [lo, hi]^2, the square a centre may lie in.
struct Uniformity {
  double ks_x = 0;  ///< Kolmogorov-Smirnov D of the x coordinates against the uniform distribution
  double ks_y = 0;
  double chi2 = 0;  ///< chi-square of the counts in a kBins x kBins grid against equal counts
};
constexpr int kBins = 10;

double ks_uniform(std::vector<double> v, double lo, double hi) {
  std::sort(v.begin(), v.end());
  const auto n = static_cast<double>(v.size());
  double d = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double f = (v[i] - lo) / (hi - lo);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}

Uniformity uniformity(const std::vector<Eigen::Vector2d>& points, double lo, double hi) {
  std::vector<double> xs, ys;
  std::array<int, kBins * kBins> counts{};
  for (const auto& p : points) {
    xs.push_back(p.x());
    ys.push_back(p.y());
    const auto bin = [&](double c) { return std::clamp(static_cast<int>((c - lo) / (hi - lo) * kBins), 0, kBins - 1); };
    ++counts[static_cast<std::size_t>(bin(p.y()) * kBins + bin(p.x()))];
  }
  Uniformity u{ks_uniform(xs, lo, hi), ks_uniform(ys, lo, hi), 0};
  const double expected = static_cast<double>(points.size()) / (kBins * kBins);
  for (const int c : counts) u.chi2 += (c - expected) * (c - expected) / expected;
  return u;
}

}  // namespace

TEST(World, PlacementIsUniform) {
  // 4000 marbles, centres uniform over [2.5, 997.5]^2 but for the rejections. Thresholds at a 0.001
  // false-alarm level each: KS D < 1.95 / sqrt(4000) = 0.0308 (asymptotic), chi-square with 99 degrees
  // of freedom < 148.2. Marbles squeezed 10% towards the centre leave a 5% strip bare on every side,
  // so their D is at least 0.05 and their chi-square in the hundreds; the end of each loop checks
  // that these thresholds do catch that. (Rejection packs centres a little more densely within a
  // marble spacing of the edges, where fewer neighbours can reject them: a strip too thin to move
  // either statistic.)
  constexpr double kKs = 1.95 / 63.245553;  // sqrt(4000)
  constexpr double kChi2 = 148.2;
  for (const std::uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    sim::WorldRequest q;
    q.objects = 4000;
    q.size = {1000, 1000};
    q.min_gap = 1;
    q.seed = seed;
    const sim::World w = sim::generate_world(q);
    const Uniformity u = uniformity(w.objects, 2.5, 997.5);
    EXPECT_LT(u.ks_x, kKs);
    EXPECT_LT(u.ks_y, kKs);
    EXPECT_LT(u.chi2, kChi2);
    std::printf("[ measured ] seed %d: KS D x %.4f, y %.4f (< %.4f); chi-square %.1f (< %.1f)\n",
                static_cast<int>(seed), u.ks_x, u.ks_y, kKs, u.chi2, kChi2);

    std::vector<Eigen::Vector2d> squeezed;
    for (const auto& p : w.objects)
      squeezed.push_back(Eigen::Vector2d(500, 500) + 0.9 * (p - Eigen::Vector2d(500, 500)));
    const Uniformity s = uniformity(squeezed, 2.5, 997.5);
    EXPECT_GT(s.ks_x, kKs);
    EXPECT_GT(s.ks_y, kKs);
    EXPECT_GT(s.chi2, kChi2);
  }
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
