// `neopipe batch` and the --shard options on the command line, without Slurm: a batch over images
// planned, run shard by shard, merged and compared with `neopipe run` on each file; sharded nav trials
// and map stats merged and compared with the unsharded runs; the bad inputs' one-line errors.
// tests/cluster/test_slurm_batch.sh runs the same on a real Slurm cluster.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "cli_test_support.hpp"

namespace neopipe::cli_testing {
namespace {

using nlohmann::json;

class BatchCli : public ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    ::setenv("NEOPIPE_CACHE_DIR", file("cache").c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  }
  std::string image(const std::string& name, int n) {
    cv::Mat m(60, 80, CV_8UC1, cv::Scalar(10));
    for (int i = 0; i < n; ++i) cv::circle(m, cv::Point(10 + 15 * i, 30), 4, cv::Scalar(200 + 10 * i), cv::FILLED);
    EXPECT_TRUE(cv::imwrite(file(name), m));
    return file(name);
  }
};

TEST_F(BatchCli, PlanRunMergeEqualsRunOnEachFile) {
  const std::vector<std::string> inputs{image("b.png", 2), image("a.png", 1), image("c.png", 3)};
  auto r = run_neopipe({"batch", "plan", inputs[0], inputs[1], inputs[2], "--out", file("out"), "--shards", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string manifest = file("out/manifest.json");
  for (const char* shard : {"1", "0"}) {
    r = run_neopipe({"batch", "run", "--manifest", manifest, "--shard", shard, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  r = run_neopipe({"batch", "status", "--manifest", manifest, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["done"], 3);
  r = run_neopipe({"batch", "merge", "--manifest", manifest, "--out", file("all.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["blobs"], 6);

  std::string expected;
  for (const std::string& in : {file("a.png"), file("b.png"), file("c.png")}) {
    const auto one = run_neopipe({"run", in, "-q"});
    ASSERT_EQ(one.exit_code, 0) << one.err;
    std::istringstream lines(one.out);
    std::string line;
    std::getline(lines, line);
    if (expected.empty()) expected = "input," + line + "\n";
    while (std::getline(lines, line)) expected += in + "," + line + "\n";
  }
  EXPECT_EQ(slurp(file("all.csv")), expected);
}

TEST_F(BatchCli, BadInputGetsOneLineErrorsAndNothingIsOverwritten) {
  const std::string a = image("a.png", 1);
  const std::string b = image("b.png", 2);
  ASSERT_EQ(run_neopipe({"batch", "plan", a, b, "--out", file("out"), "--shards", "2", "-q"}).exit_code, 0);
  const std::string manifest = file("out/manifest.json");
  const std::string before = slurp(manifest);
  EXPECT_TRUE(one_error_line(run_neopipe({"batch", "run", "--manifest", manifest, "--shard", "2"}), "out of range"));
  EXPECT_TRUE(one_error_line(run_neopipe({"batch", "plan", a, "--out", file("out"), "-q"}), "another manifest"));
  EXPECT_EQ(slurp(manifest), before);
  EXPECT_TRUE(one_error_line(run_neopipe({"batch", "plan", file("none.mp4"), "--out", file("o2"), "-q"}), "none.mp4"));
  // An edited manifest (say, another version's).
  write_text(file("old.json"), std::regex_replace(before, std::regex("\"neopipe_version\": \"[^\"]*\""),
                                                  "\"neopipe_version\": \"0.0.1\""));
  EXPECT_TRUE(one_error_line(run_neopipe({"batch", "run", "--manifest", file("old.json"), "--shard", "0"}), "0.0.1"));
  // No sbatch on PATH: the error says so, and the dry run still prints the script.
  const std::string path = ::getenv("PATH") ? ::getenv("PATH") : "";
  ::setenv("PATH", file("empty").c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  const auto no_sbatch = run_neopipe({"batch", "submit", "--manifest", manifest});
  const auto dry = run_neopipe({"batch", "submit", "--manifest", manifest, "--dry-run", "--max-parallel", "1"});
  ::setenv("PATH", path.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  EXPECT_TRUE(one_error_line(no_sbatch, "sbatch")) << no_sbatch.err;
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("#SBATCH --array=0-1%1"), std::string::npos) << dry.out;
}

// Slurm's sbatch stood in for by scripts: one that refuses (as for an unknown partition), one that
// accepts and answers a job id, which submit prints and records.
TEST_F(BatchCli, SubmitReportsSbatchsRefusalAndRecordsTheJobId) {
  const std::string a = image("a.png", 1);
  ASSERT_EQ(run_neopipe({"batch", "plan", a, "--out", file("out"), "-q"}).exit_code, 0);
  const std::string manifest = file("out/manifest.json");
  fs::create_directories(file("refuse"));
  fs::create_directories(file("accept"));
  write_text(file("refuse/sbatch"),
             "#!/bin/sh\necho 'sbatch: error: Batch job submission failed: Invalid partition name specified' >&2\n"
             "exit 1\n");
  write_text(file("accept/sbatch"), "#!/bin/sh\necho 4242\n");
  for (const char* f : {"refuse/sbatch", "accept/sbatch"}) {
    fs::permissions(file(f), fs::perms::owner_all);
  }
  const std::string path = ::getenv("PATH") ? ::getenv("PATH") : "";
  ::setenv("PATH", (file("refuse") + ":" + path).c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  const auto refused = run_neopipe({"batch", "submit", "--manifest", manifest, "--partition", "nope"});
  ::setenv("PATH", (file("accept") + ":" + path).c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  const auto accepted = run_neopipe({"batch", "submit", "--manifest", manifest});
  ::setenv("PATH", path.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): one thread
  EXPECT_TRUE(one_error_line(refused, "Invalid partition name")) << refused.err;
  EXPECT_EQ(accepted.exit_code, 0) << accepted.err;
  EXPECT_EQ(accepted.out, "4242\n");
  EXPECT_NE(slurp(file("out/jobs.json")).find("\"4242\""), std::string::npos);
}

TEST_F(BatchCli, ShardedNavTrialsMergeToTheUnshardedRun) {
  ASSERT_EQ(run_neopipe({"sim", "world", "--objects", "60", "--seed", "3", "--out", file("w.yaml")}).exit_code, 0);
  const std::vector<std::string> base{"nav",    "--world", file("w.yaml"), "--trials", "5",
                                      "--seed", "5",       "--sigma-map",  "0.5",      "--json"};
  const auto whole = run_neopipe(base);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  std::vector<std::string> merge{"batch", "merge-shards"};
  for (const char* shard : {"2/3", "0/3", "1/3"}) {
    auto args = base;
    args.insert(args.end(), {"--shard", shard, "--threads", "1"});
    const auto r = run_neopipe(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string name = file(std::string("shard") + shard[0] + ".json");
    write_text(name, r.out);
    merge.push_back(name);
  }
  const auto merged = run_neopipe(merge);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  // Byte for byte the unsharded JSON, without its two wall-time fields.
  const std::string untimed =
      std::regex_replace(std::regex_replace(whole.out, std::regex("\"frames_per_second\":[^,]*,"), ""),
                         std::regex("\"seconds\":[^,]*,"), "");
  EXPECT_EQ(merged.out, untimed);
  merge.pop_back();
  EXPECT_TRUE(one_error_line(run_neopipe(merge), "missing"));
  auto bad = base;
  bad.insert(bad.end(), {"--shard", "3/3"});
  EXPECT_TRUE(one_error_line(run_neopipe(bad), "out of range"));
  bad.erase(bad.begin() + 9);  // --json
  EXPECT_TRUE(one_error_line(run_neopipe(bad), "--shard goes with --trials N --json"));
}

TEST_F(BatchCli, ShardedMapStatsMergeToTheUnshardedCsv) {
  const std::vector<std::string> base{"map",          "stats",    "--size",   "50", "--window", "4,6,8",
                                      "--population", "0..40:10", "--trials", "3",  "-q"};
  const auto whole = run_neopipe(base);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  std::vector<std::string> merge{"batch", "merge-shards", "--out", file("merged.csv")};
  for (const char* shard : {"3/4", "1/4", "0/4", "2/4"}) {
    auto args = base;
    args.insert(args.end(), {"--shard", shard, "--csv", file(std::string("s") + shard[0] + ".csv")});
    const auto r = run_neopipe(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    merge.push_back(file(std::string("s") + shard[0] + ".csv"));
  }
  const auto merged = run_neopipe(merge);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(slurp(file("merged.csv")), whole.out);
  auto bad = base;
  bad.insert(bad.end(), {"--shard", "4/4"});
  EXPECT_TRUE(one_error_line(run_neopipe(bad), "out of range"));
}

}  // namespace
}  // namespace neopipe::cli_testing
