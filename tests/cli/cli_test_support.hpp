#pragma once
// Running the neopipe binary from the command-line tests: separate stdout and stderr, a timeout,
// exit code or signal.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace neopipe::cli_testing {
namespace fs = std::filesystem;

constexpr int kTimeoutSeconds = 60;

struct RunResult {
  bool timed_out = false;
  bool signaled = false;
  int signal = 0;
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

inline std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f << text;
}

inline std::string describe(const std::vector<std::string>& args) {
  std::string s = "neopipe";
  for (const auto& a : args) s += " " + a;
  return s;
}

/// Starts NEOPIPE_BINARY with `args` and stdin from /dev/null; stdout and stderr go to the files
/// given, or stay the test's when empty. Returns the child's pid, or 0 (and a test failure).
inline pid_t spawn_neopipe(const std::vector<std::string>& args, const std::string& out_path = "",
                           const std::string& err_path = "") {
  std::vector<std::string> argv_s{NEOPIPE_BINARY};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (!out_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (!err_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    ADD_FAILURE() << "posix_spawn(" << argv[0] << ") failed: " << std::strerror(rc);
    return 0;
  }
  return pid;
}

/// Runs NEOPIPE_BINARY with `args`, stdin from /dev/null, stdout and stderr captured separately
/// (through files, so a chatty child never blocks on a full pipe). Kills it after kTimeoutSeconds.
inline RunResult run_neopipe(const std::vector<std::string>& args) {
  static int counter = 0;
  const fs::path capture =
      fs::temp_directory_path() / ("neopipe_cli_capture_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
  const std::string out_path = capture.string() + ".out";
  const std::string err_path = capture.string() + ".err";
  const pid_t pid = spawn_neopipe(args, out_path, err_path);
  RunResult r;
  if (pid == 0) return r;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kTimeoutSeconds);
  int status = 0;
  for (;;) {
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) {
      ADD_FAILURE() << "waitpid failed: " << std::strerror(errno);
      return r;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) {
    r.signaled = true;
    r.signal = WTERMSIG(status);
  }
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  fs::remove(out_path);
  fs::remove(err_path);
  EXPECT_FALSE(r.timed_out) << describe(args) << ": killed after " << kTimeoutSeconds << " s";
  return r;
}

/// A CSV table of numbers: the header line into `header`, then each row's cells.
inline std::vector<std::vector<double>> csv_numbers(const std::string& text, std::string* header = nullptr) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (header != nullptr) *header = line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

/// Failed cleanly (no signal) with exactly one line on stderr, which contains `needle`.
inline bool one_error_line(const RunResult& r, const std::string& needle) {
  return r.exit_code != 0 && !r.signaled && r.err.find(needle) != std::string::npos &&
         std::count(r.err.begin(), r.err.end(), '\n') == 1;
}

/// A fresh folder per test, removed afterwards.
class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("neopipe_cli_" + std::to_string(getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  [[nodiscard]] std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

}  // namespace neopipe::cli_testing
