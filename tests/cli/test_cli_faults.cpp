// `neopipe run` when the world around it fails (issue 18, "Load and faults"): a full disk, a signal
// mid-run, a closed output pipe, an input cut short while it is read. Each ends with a clean error or a clean end, the
// documented exit status, and a table whose rows are whole frames, every line complete.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "cli_test_support.hpp"

namespace {
namespace fs = std::filesystem;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)

const std::string kVideo = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";  // 795 frames, 10 fps

class RunFaults : public ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    if (!fs::exists(kVideo)) GTEST_SKIP() << kVideo << " not installed";
  }
};

// The rows of a CSV blob table: every line complete and of 11 numbers, frame numbers never going
// back. Returns how far into the video the table reaches (the last frame's number + 1), or -1 if the
// table is broken. Frames may be missing: a paced run drops the frames that find the pipeline full,
// and a loaded machine (CI runs two suites at once) drops some.
std::int64_t whole_frames(const std::string& table) {
  if (table.empty() || table.back() != '\n') return -1;
  std::string header;
  std::int64_t last = -1;
  for (const auto& row : csv_numbers(table, &header)) {
    if (row.size() != 11) return -1;
    const auto frame = static_cast<std::int64_t>(row[0]);
    if (frame < last) return -1;
    last = frame;
  }
  return header.rfind("frame,blob,area", 0) == 0 ? last + 1 : -1;
}

TEST_F(RunFaults, AFullDiskIsOneLineNamingTheFileAndTheCause) {
  const RunResult r = run_neopipe({"run", kVideo, "--out", "/dev/full", "--format", "csv", "-q"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(one_error_line(r, "/dev/full: write failed: No space left on device")) << r.err;
}

// Starts a paced run, waits until it has written a few frames, sends `signal`, and checks the end.
void stop_mid_run(const std::string& table, int signal, int expected_status) {
  const pid_t pid = spawn_neopipe({"run", kVideo, "--realtime", "--fps", "50", "--out", table, "-q"});
  ASSERT_NE(pid, 0);
  // Paced at 50 frames/s the video lasts 16 s: the signal lands mid-run however loaded the machine.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kTimeoutSeconds);
  while (whole_frames(slurp(table)) < 5 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), expected_status);
  const std::int64_t frames = whole_frames(slurp(table));
  EXPECT_GE(frames, 5);
  EXPECT_LT(frames, 795) << "the run ended before the signal: the test proves nothing";
}

TEST_F(RunFaults, SigtermMidRunWritesEveryFrameReadAndExits143) {
  stop_mid_run(file("t.csv"), SIGTERM, 143);
}

TEST_F(RunFaults, CtrlCMidRunWritesEveryFrameReadAndExits130) {
  stop_mid_run(file("i.csv"), SIGINT, 130);
}

// The input is cut to a third while a paced run reads it (a download or a copy that failed, a
// recording rotated away): the frames before the cut are written whole, and the run ends with one
// line naming the file and where decoding stopped, exit 1, after the summary.
TEST_F(RunFaults, AnInputTruncatedWhileReadEndsWithOneLineAndWholeRows) {
  const std::string input = file("cut.avi");
  fs::copy_file(kVideo, input);
  const std::string table = file("cut.csv");
  const std::string err = file("cut.err");
  const pid_t pid = spawn_neopipe({"run", input, "--realtime", "--fps", "50", "--out", table}, "", err);
  ASSERT_NE(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kTimeoutSeconds);
  while (whole_frames(slurp(table)) < 5 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(::truncate(input.c_str(), static_cast<off_t>(fs::file_size(input) / 3)), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string messages = slurp(err);
  EXPECT_NE(messages.find("neopipe run: error: " + input + ": decoding stopped at frame "), std::string::npos)
      << messages;
  EXPECT_NE(messages.find("(truncated or corrupt video)\n"), std::string::npos) << messages;
  const std::int64_t frames = whole_frames(slurp(table));
  EXPECT_GE(frames, 5);
  EXPECT_LT(frames, 795 / 2) << "a third of the file cannot hold half the frames";
}

// A reader that stops early (`| head -1`) ends the run as it ends any filter: SIGPIPE, status 141
// in the shell, and nothing on stderr.
TEST_F(RunFaults, AClosedPipeEndsTheRunQuietly) {
  write_text(file("pipe.sh"), "set -o pipefail\n'" + std::string(NEOPIPE_BINARY) + "' run '" + kVideo + "' -q 2> '" +
                                  file("err") + "' | head -1 > '" + file("first") + "'\necho $?\n");
  FILE* shell = popen(("bash '" + file("pipe.sh") + "'").c_str(), "r");
  ASSERT_NE(shell, nullptr);
  std::string out;
  std::array<char, 64> chunk{};
  while (fgets(chunk.data(), chunk.size(), shell) != nullptr) out += chunk.data();
  EXPECT_EQ(pclose(shell), 0);
  EXPECT_EQ(out, "141\n");
  EXPECT_EQ(slurp(file("first")).rfind("frame,blob,area", 0), 0U);
  EXPECT_EQ(slurp(file("err")), "");
}

}  // namespace
