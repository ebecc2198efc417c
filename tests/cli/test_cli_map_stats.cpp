// `neopipe map stats`: the CSV's header and rows, the PNG, identical output for any thread count,
// and bad input as one line and a non-zero exit.

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "cli_test_support.hpp"

namespace {
namespace fs = std::filesystem;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)

using MapStatsCli = ScratchDirTest;

const std::vector<std::string> kSmall{"map",          "stats",    "--size",   "50", "--window", "4,6",
                                      "--population", "0..40:20", "--trials", "3",  "-q"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

TEST_F(MapStatsCli, CsvHasOneRowPerWindowAndPopulation) {
  const auto r = run_neopipe(kSmall);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string header;
  const auto rows = csv_numbers(r.out, &header);
  EXPECT_EQ(header.rfind("window,margin,population,trials,density,general_parkways_mean,general_parkways_sd,"
                         "general_parkways_ci_low,general_parkways_ci_high,",
                         0),
            0U)
      << header;
  for (const char* column : {"isolated_objects_mean", "obvious_parkways_mean", "isolated_parkways_mean",
                             "scc_with_trajectories_mean", "new_parkways_ci_high", "poisson_new_parkways_bounded"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column;
  }
  const auto columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',') + 1);
  EXPECT_EQ(columns, 5U + 4U * 10U + 3U);
  ASSERT_EQ(rows.size(), 6U);
  const std::vector<double> windows{4, 4, 4, 6, 6, 6};
  const std::vector<double> populations{0, 20, 40, 0, 20, 40};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), columns);
    EXPECT_EQ(rows[i][0], windows[i]);
    EXPECT_DOUBLE_EQ(rows[i][1], 0.05 * windows[i]);
    EXPECT_EQ(rows[i][2], populations[i]);
    EXPECT_EQ(rows[i][3], 3);
    EXPECT_LE(rows[i][5], populations[i]);  // no more parkways than objects
  }
  EXPECT_EQ(rows[0][5], 0);  // population 0: nothing
}

TEST_F(MapStatsCli, CsvFileAndPlotAreTheSameForAnyThreadCount) {
  const auto one = run_neopipe(with(kSmall, {"--threads", "1", "--csv", file("one.csv"), "--plot", file("s.png")}));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_TRUE(one.out.empty());
  const auto two = run_neopipe(with(kSmall, {"--threads", "2"}));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(slurp(file("one.csv")), two.out);
  const cv::Mat png = cv::imread(file("s.png"));
  ASSERT_FALSE(png.empty());
  EXPECT_GE(png.cols, 800);
  EXPECT_GE(png.rows, 600);
}

TEST_F(MapStatsCli, HelpDescribesTheOptions) {
  const auto r = run_neopipe({"map", "stats", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option :
       {"--size", "--window", "--population", "--trials", "--seed", "--threads", "--csv", "--plot"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
}

TEST_F(MapStatsCli, BadInputIsOneLineAndNonZero) {
  const std::vector<std::string> base{"map", "stats", "--population", "0..20", "--trials", "1", "-q"};
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--window", "100", "--size", "100"})), "--window"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--window", "2..x"})), "--window"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--window", "0"})), "--window"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "stats", "--population", "10..5"}), "--population"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "stats", "--population", "0..100:0"}), "--population"));
  EXPECT_TRUE(one_error_line(run_neopipe({"map", "stats", "--population", "2.5"}), "--population"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--trials", "0"})), "--trials"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--size", "-3"})), "--size"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--plot", file("s.jpg")})), "--plot"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--csv", file("no/such/dir/s.csv")})), "--csv"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--plot", file("no/such/dir/s.png")})), "--plot"));
  EXPECT_TRUE(one_error_line(run_neopipe(with(base, {"--threads", "-1"})), "--threads"));
  // `neopipe map` itself still needs a world.
  EXPECT_TRUE(one_error_line(run_neopipe({"map"}), "--world"));
}
