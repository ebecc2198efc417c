// neopipe batch without Slurm: shards, the checksum, the manifest and its guards, a shard run that
// resumes and isolates a corrupt input, the merge, the sharded-table merge and the sbatch script.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "batch/checksum.hpp"
#include "batch/manifest.hpp"
#include "batch/merge.hpp"
#include "batch/shard.hpp"
#include "batch/shard_runner.hpp"
#include "batch/slurm.hpp"
#include "batch/stats_shards.hpp"

namespace neopipe::batch {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

class BatchFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("neopipe_batch_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "in");
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A gray image with `n` bright squares on a dark ground: n blobs.
  fs::path image(const std::string& name, int n) {
    cv::Mat m(60, 80, CV_8UC1, cv::Scalar(10));
    for (int i = 0; i < n; ++i) cv::rectangle(m, cv::Rect(4 + 15 * i, 20, 8, 8), cv::Scalar(240), cv::FILLED);
    const fs::path p = dir_ / "in" / name;
    EXPECT_TRUE(cv::imwrite(p.string(), m));
    return p;
  }
  PlanRequest request(std::vector<std::string> inputs, std::int64_t shards) {
    PlanRequest r;
    r.inputs = std::move(inputs);
    r.out = (dir_ / "out").string();
    r.shards = shards;
    return r;
  }
  fs::path dir_;
};

// ------------------------------------------------------------------------------------------------
TEST(Shard, BlocksTileTheItemsAndDifferByAtMostOne) {
  for (std::int64_t n : {0, 1, 7, 100, 101}) {
    for (std::int64_t k : {1, 2, 3, 7, 10}) {
      std::int64_t next = 0;
      std::int64_t smallest = n + 1;
      std::int64_t largest = -1;
      for (std::int64_t i = 0; i < k; ++i) {
        const ItemRange r = shard_range(n, {i, k});
        EXPECT_EQ(r.first, next) << n << " items, shard " << i << "/" << k;
        next = r.last;
        smallest = std::min(smallest, r.size());
        largest = std::max(largest, r.size());
      }
      EXPECT_EQ(next, n);
      EXPECT_LE(largest - smallest, 1);
    }
  }
}

TEST(Shard, ParsesIOfKAndRefusesTheRest) {
  const ShardSpec s = parse_shard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"5/5", "-1/3", "1", "a/3", "1/0", "1/3x", ""}) {
    EXPECT_THROW(parse_shard(bad), std::invalid_argument) << bad;
  }
  try {
    parse_shard("7/4");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

TEST(Shard, GridRunsCoverTheRangeInRowMajorOrder) {
  // 3 windows x 4 populations, cells 2..9: window 0 pops 2-3, window 1 pops 0-3, window 2 pops 0-1.
  const auto runs = grid_runs(3, 4, {2, 10});
  ASSERT_EQ(runs.size(), 3U);
  EXPECT_EQ(runs[0].outer, 0U);
  EXPECT_EQ(runs[0].inner_first, 2U);
  EXPECT_EQ(runs[0].inner_last, 4U);
  EXPECT_EQ(runs[1].inner_first, 0U);
  EXPECT_EQ(runs[1].inner_last, 4U);
  EXPECT_EQ(runs[2].outer, 2U);
  EXPECT_EQ(runs[2].inner_last, 2U);
}

// ------------------------------------------------------------------------------------------------
TEST(ChecksumTest, StreamingEqualsOneShotWhereverTheBytesAreSplit) {
  std::vector<unsigned char> bytes(100);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 37 + 11);
  Checksum whole;
  whole.update(bytes);
  for (std::size_t a = 0; a <= bytes.size(); a += 3) {
    for (std::size_t b = a; b <= bytes.size(); b += 7) {
      Checksum parts;
      parts.update(std::span(bytes).subspan(0, a));
      parts.update(std::span(bytes).subspan(a, b - a));
      parts.update(std::span(bytes).subspan(b));
      EXPECT_EQ(parts.value(), whole.value()) << a << "," << b;
    }
  }
}

TEST(ChecksumTest, EverySingleBitFlipAndLengthChangesIt) {
  std::vector<unsigned char> bytes(37, 0);
  Checksum base;
  base.update(bytes);
  std::set<std::uint64_t> seen{base.value()};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      auto changed = bytes;
      changed[i] ^= static_cast<unsigned char>(1U << bit);
      Checksum c;
      c.update(changed);
      EXPECT_TRUE(seen.insert(c.value()).second) << "byte " << i << " bit " << bit;
    }
  }
  // Zero bytes appended change it too (the length goes in).
  Checksum longer;
  longer.update(std::vector<unsigned char>(38, 0));
  EXPECT_NE(longer.value(), base.value());
  // Pinned: manifests of earlier runs hold these digests, so the function must never change. The
  // values come from an independent implementation of checksum.hpp's description (Python:
  // little-endian words, s = (s ^ w) * P then s ^= s >> 32, tail bytes, length, fmix64).
  EXPECT_EQ(text_checksum(""), "b8371b5e9326a9e3");
  EXPECT_EQ(text_checksum("neopipe"), "b36633376c353cc5");               // tail only
  EXPECT_EQ(text_checksum("0123456789abcdef0123"), "f257d687699e5a0f");  // two words and a tail
  EXPECT_NE(text_checksum("neopipe"), text_checksum("neopipf"));
}

// ------------------------------------------------------------------------------------------------
TEST_F(BatchFolder, PlanSortsChecksumsAndDealsInputsRoundRobin) {
  image("c.png", 1);
  image("a.png", 2);
  image("b.png", 3);
  write_text(dir_ / "list.txt", "# the three images\nin/c.png\n\nin/a.png\nin/b.png\nin/a.png\n");
  const Manifest m = plan_manifest(request({(dir_ / "list.txt").string()}, 2));
  ASSERT_EQ(m.inputs.size(), 3U);  // the duplicate gone
  EXPECT_EQ(fs::path(m.inputs[0].path).filename(), "a.png");
  EXPECT_EQ(fs::path(m.inputs[2].path).filename(), "c.png");
  EXPECT_EQ(m.inputs[0].shard, 0);
  EXPECT_EQ(m.inputs[1].shard, 1);
  EXPECT_EQ(m.inputs[2].shard, 0);
  EXPECT_EQ(m.inputs[1].checksum, file_checksum(dir_ / "in" / "b.png"));
  EXPECT_EQ(m.id, manifest_id(m));
  // The same inputs planned again: the same manifest, byte for byte.
  EXPECT_EQ(manifest_json(plan_manifest(request({(dir_ / "list.txt").string()}, 2))).dump(), manifest_json(m).dump());
}

TEST_F(BatchFolder, PlanRefusesMissingInputsAndTooManyShards) {
  image("a.png", 1);
  EXPECT_THROW(plan_manifest(request({(dir_ / "in" / "nope.mp4").string()}, 1)), BatchError);
  EXPECT_THROW(plan_manifest(request({(dir_ / "in" / "a.png").string()}, 2)), BatchError);
  EXPECT_THROW(plan_manifest(request({(dir_ / "in").string()}, 1)), BatchError);  // a folder without videos
}

TEST_F(BatchFolder, AnOutputFolderHoldsOneManifest) {
  image("a.png", 1);
  image("b.png", 2);
  const Manifest m = plan_manifest(request({(dir_ / "in" / "a.png").string(), (dir_ / "in" / "b.png").string()}, 1));
  EXPECT_TRUE(write_manifest(m));
  EXPECT_FALSE(write_manifest(m));  // the same again: no change
  const std::string before = slurp(m.manifest_path());
  const Manifest other = plan_manifest(request({(dir_ / "in" / "a.png").string()}, 1));
  EXPECT_THROW(write_manifest(other), BatchError);
  EXPECT_EQ(slurp(m.manifest_path()), before);  // nothing overwritten
}

TEST_F(BatchFolder, LoadRefusesEditedManifestsAndOtherVersions) {
  image("a.png", 1);
  const Manifest m = plan_manifest(request({(dir_ / "in" / "a.png").string()}, 1));
  write_manifest(m);
  EXPECT_NO_THROW(load_manifest(m.manifest_path()));
  nlohmann::json j = manifest_json(m);
  j["inputs"][0]["checksum"] = "0000000000000000";
  write_text(dir_ / "edited.json", j.dump());
  EXPECT_THROW(load_manifest(dir_ / "edited.json"), BatchError);
  j = manifest_json(m);
  j["neopipe_version"] = "0.0.1";
  write_text(dir_ / "old.json", j.dump());
  try {
    load_manifest(dir_ / "old.json");
    ADD_FAILURE() << "a manifest of neopipe 0.0.1 was accepted";
  } catch (const BatchError& e) {
    EXPECT_NE(std::string(e.what()).find("0.0.1"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------------------------------------
TEST_F(BatchFolder, ShardRunsResumeIsolateACorruptInputAndMerge) {
  image("a.png", 1);
  image("b.png", 2);
  image("c.png", 3);
  write_text(dir_ / "in" / "bad.png", "not an image");
  const Manifest m = plan_manifest(request({(dir_ / "in").string() + "/a.png", (dir_ / "in" / "b.png").string(),
                                            (dir_ / "in" / "bad.png").string(), (dir_ / "in" / "c.png").string()},
                                           2));
  write_manifest(m);
  EXPECT_THROW(run_shard(m, 2, {}), BatchError);  // out of range

  ShardRunOptions o;
  o.threads = 1;
  ShardReport r0 = run_shard(m, 0, o);  // a.png, bad.png
  EXPECT_EQ(r0.done, 1);
  EXPECT_EQ(r0.failed, 1);
  ShardReport r1 = run_shard(m, 1, o);  // b.png, c.png
  EXPECT_EQ(r1.done, 2);
  EXPECT_EQ(r1.failed, 0);
  const BatchSummary s = summarise_batch(m);
  EXPECT_EQ(s.done, 3);
  EXPECT_EQ(s.failed, 1);
  ASSERT_EQ(s.failures.size(), 1U);
  EXPECT_NE(s.failures[0].first.find("bad.png"), std::string::npos);
  EXPECT_FALSE(s.failures[0].second.empty());
  EXPECT_EQ(s.blobs, 1 + 2 + 3);

  // Again: the done inputs are skipped, the failed one retried (and fails again).
  r1 = run_shard(m, 1, o);
  EXPECT_EQ(r1.skipped, 2);
  EXPECT_EQ(r1.done, 0);
  // A lost marker (a task killed between table and marker): that input alone runs again.
  fs::remove(m.done_path(m.inputs[3]));
  r1 = run_shard(m, 1, o);
  EXPECT_EQ(r1.skipped, 1);
  EXPECT_EQ(r1.done, 1);

  const fs::path merged = dir_ / "all.csv";
  merge_tables(m, merged, false);
  std::istringstream lines(slurp(merged));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("input,frame,blob,area", 0), 0U) << line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 6U);
  EXPECT_EQ(rows[0].rfind(m.inputs[0].path + ",0,", 0), 0U) << rows[0];  // a.png first, manifest order
  EXPECT_EQ(rows[5].rfind(m.inputs[3].path + ",0,", 0), 0U) << rows[5];  // c.png last
  EXPECT_THROW(merge_tables(m, dir_ / "all.jsonl", false), BatchError);  // csv tables
}

TEST_F(BatchFolder, AChangedInputFailsAloneAndPendingInputsBlockTheMerge) {
  image("a.png", 1);
  const fs::path b = image("b.png", 2);
  const Manifest m = plan_manifest(request({(dir_ / "in" / "a.png").string(), b.string()}, 1));
  write_manifest(m);
  EXPECT_THROW(merge_tables(m, dir_ / "all.csv", false), BatchError);  // nothing done yet
  image("b.png", 3);                                                   // changed after planning
  const ShardReport r = run_shard(m, 0, {});
  EXPECT_EQ(r.done, 1);
  EXPECT_EQ(r.failed, 1);
  const BatchSummary s = summarise_batch(m);
  ASSERT_EQ(s.failures.size(), 1U);
  EXPECT_NE(s.failures[0].second.find("changed since planning"), std::string::npos) << s.failures[0].second;
}

TEST(Merge, CsvFieldsQuoteWhatNeedsIt) {
  EXPECT_EQ(csv_field("/a/b.mp4"), "/a/b.mp4");
  EXPECT_EQ(csv_field("/a,b.mp4"), "\"/a,b.mp4\"");
  EXPECT_EQ(csv_field("/a\"b.mp4"), "\"/a\"\"b.mp4\"");
}

// ------------------------------------------------------------------------------------------------
TEST(ShardTables, MergeConcatenatesInOrderAndChecksCoverage) {
  const std::string header = "a,b\n";
  const auto shard = [&](int i, int k, int first, int last, const std::string& rows) {
    return shard_table_line({i, k}, {first, last}, 3) + header + rows;
  };
  const std::string s0 = shard(0, 2, 0, 2, "1,2\n3,4\n");
  const std::string s1 = shard(1, 2, 2, 3, "5,6\n");
  EXPECT_EQ(merge_shard_tables({s1, s0}, {"s1", "s0"}), "a,b\n1,2\n3,4\n5,6\n");
  EXPECT_THROW(merge_shard_tables({s0}, {"s0"}), BatchError);                                   // missing
  EXPECT_THROW(merge_shard_tables({s0, s0, s1}, {"a", "b", "c"}), BatchError);                  // twice
  EXPECT_THROW(merge_shard_tables({s0, "a,b\n5,6\n"}, {"s0", "plain"}), BatchError);            // not a shard
  EXPECT_THROW(merge_shard_tables({s0, shard(1, 3, 2, 3, "5,6\n")}, {"s0", "x"}), BatchError);  // other K
}

// ------------------------------------------------------------------------------------------------
TEST(Slurm, ArraySpecsAndTheScript) {
  EXPECT_EQ(array_spec({0, 1, 2, 3}, 2), "0-3%2");
  EXPECT_EQ(array_spec({5, 1, 3, 4}, 0), "1,3-5");
  EXPECT_EQ(array_spec({7}, 0), "7");
  Manifest m;
  m.id = "0123456789abcdef";
  m.out = "/shared/run 1";
  m.shards = 4;
  SubmitOptions o;
  o.neopipe = "/opt/neopipe/bin/neopipe";
  o.partition = "short";
  o.time = "0:30:00";
  o.max_parallel = 2;
  const std::string s = sbatch_script(m, o);
  EXPECT_NE(s.find("#SBATCH --array=0-3%2\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --partition=short\n"), std::string::npos) << s;
  EXPECT_NE(s.find("#SBATCH --time=0:30:00\n"), std::string::npos) << s;
  EXPECT_EQ(s.find("--mem"), std::string::npos) << s;
  EXPECT_NE(s.find("'/shared/run 1/manifest.json' --shard \"$SLURM_ARRAY_TASK_ID\""), std::string::npos) << s;
  EXPECT_EQ(s.rfind("#!/bin/bash\n", 0), 0U);
}

}  // namespace
}  // namespace neopipe::batch
