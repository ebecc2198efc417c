// End-to-end tests of the `neopipe` command-line tool: the built binary is run as a child process
// on inputs generated here (lossless FFV1 .mkv and MJPG .avi videos of white disks with known
// centres moving on black, PNG images, directories), and its exit status, stdout, stderr and output
// files are checked:
//   * `run`: the blob table (CSV / JSON Lines, --moments, --threshold, --connectivity, stdout vs
//     --out), centroids against the known disk centres, frame numbering and blob order, the stderr
//     summary, images / image lists / directories as input;
//   * determinism across --threads for the built-in graph and an example graph, and
//     examples/blobs.yaml == the built-in graph byte for byte;
//   * --annotate into a video and into PNG files; --realtime accounting (processed + dropped), and
//     frames dropped while the sink is blocked;
//   * bad input and bad command lines: a non-zero exit (2 for command-line errors), no signal, exactly
//     one "error:" line naming the input and the cause, rows of already processed frames kept;
//     graph spec errors reported as "path:line:col:";
//   * --help texts, --list-kernels, and `bench`: the chain case, --sweep size and blobs, thread lists
//     and --scaling, --video (decode-only and run rates; bad files as one-line errors), --json.
// Every child runs under a timeout so that a hang fails the test instead of blocking the run.
// Set NEOPIPE_CLI_KEEP_TMP=1 to keep the generated inputs and the outputs for a look afterwards.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_test_support.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace neopipe::cli_testing;  // NOLINT(google-build-using-namespace)

const std::string kHeader = "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy";

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) parts.push_back(part);
  if (!s.empty() && s.back() == sep) parts.emplace_back();
  return parts;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

/// Asserts a successful run (exit 0, no signal) and returns whether it was one.
::testing::AssertionResult succeeded(const RunResult& r) {
  if (r.timed_out) return ::testing::AssertionFailure() << "timed out";
  if (r.signaled) return ::testing::AssertionFailure() << "killed by signal " << r.signal << "\nstderr:\n" << r.err;
  if (r.exit_code != 0) {
    return ::testing::AssertionFailure() << "exit code " << r.exit_code << "\nstderr:\n" << r.err;
  }
  return ::testing::AssertionSuccess();
}

/// The checks every failure must pass: a non-zero exit that is not a signal, and the last
/// non-empty stderr line is the only line mentioning "error" and contains "error:" and each of
/// `needles`. Returns that line ("" if the checks failed).
std::string expect_one_error(const RunResult& r, const std::vector<std::string>& needles,
                             std::optional<int> code = std::nullopt) {
  EXPECT_FALSE(r.timed_out);
  EXPECT_FALSE(r.signaled) << "killed by signal " << r.signal << " (a crash)\nstderr:\n" << r.err;
  EXPECT_NE(r.exit_code, 0) << "stderr:\n" << r.err;
  if (code) {
    EXPECT_EQ(r.exit_code, *code) << "stderr:\n" << r.err;
  }
  std::vector<std::string> lines;
  for (const auto& l : split_lines(r.err)) {
    if (l.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(l);
  }
  if (lines.empty()) {
    ADD_FAILURE() << "stderr is empty; expected one error line";
    return "";
  }
  const std::string& last = lines.back();
  EXPECT_TRUE(contains(last, "error:")) << "last stderr line: " << last << "\nstderr:\n" << r.err;
  for (size_t i = 0; i + 1 < lines.size(); ++i) {
    EXPECT_FALSE(contains(lower(lines[i]), "error")) << "another stderr line mentions an error: " << lines[i];
  }
  for (const auto& n : needles) EXPECT_TRUE(contains(last, n)) << "error line lacks '" << n << "': " << last;
  return last;
}

// ---------------------------------------------------------------------------------------------
// The scene: white disks with known centres on black

constexpr int kW = 160;
constexpr int kH = 120;
constexpr int kFrames = 20;

struct Disk {
  cv::Point centre;
  int radius;
  int value = 255;
};

/// Frame k of the moving scene: disk A moves right, disk B moves down, disk C stands still. B's
/// top row is above A's for k < 6 and below it after, so the raster order of the blobs changes.
std::vector<Disk> scene(int k) {
  return {{{30 + 3 * k, 40}, 8}, {{100, 30 + 2 * k}, 10}, {{140, 100}, 6}};
}

cv::Mat disk_mask(const Disk& d, cv::Size size = {kW, kH}) {
  cv::Mat m = cv::Mat::zeros(size, CV_8UC1);
  cv::circle(m, d.centre, d.radius, cv::Scalar(255), cv::FILLED, cv::LINE_8);
  return m;
}

cv::Mat render(const std::vector<Disk>& disks, cv::Size size = {kW, kH}) {
  cv::Mat img = cv::Mat::zeros(size, CV_8UC3);
  for (const auto& d : disks) {
    cv::circle(img, d.centre, d.radius, cv::Scalar(d.value, d.value, d.value), cv::FILLED, cv::LINE_8);
  }
  return img;
}

/// What the blob table should say about one disk, computed from its own mask.
struct ExpectedBlob {
  int first_pixel;  ///< y * width + x of its first pixel in raster order
  double cx, cy;
  std::int64_t area;
  cv::Rect box;
  double mu20, mu11, mu02;
};

/// The disks of a frame as blobs, in the order the table must list them.
std::vector<ExpectedBlob> expected_blobs(const std::vector<Disk>& disks, cv::Size size = {kW, kH}) {
  std::vector<ExpectedBlob> out;
  for (const auto& d : disks) {
    const cv::Mat m = disk_mask(d, size);
    std::vector<cv::Point> pts;
    cv::findNonZero(m, pts);
    int first = size.area();
    for (const auto& p : pts) first = std::min(first, p.y * size.width + p.x);
    const cv::Moments mo = cv::moments(m, true);
    out.push_back({first, double(d.centre.x), double(d.centre.y), static_cast<std::int64_t>(pts.size()),
                   cv::boundingRect(pts), mo.mu20, mo.mu11, mo.mu02});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first_pixel < b.first_pixel; });
  return out;
}

// ---------------------------------------------------------------------------------------------
// The blob table

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  ///< as printed

  int col(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
  }
  double num(size_t row, const std::string& name) const {
    const int c = col(name);
    if (c < 0 || static_cast<size_t>(c) >= rows[row].size()) {
      ADD_FAILURE() << "no column " << name;
      return 0;
    }
    return std::stod(rows[row][static_cast<size_t>(c)]);
  }
  std::int64_t integer(size_t row, const std::string& name) const { return static_cast<std::int64_t>(num(row, name)); }
  /// Row indices of each frame, in table order.
  std::map<std::int64_t, std::vector<size_t>> by_frame() const {
    std::map<std::int64_t, std::vector<size_t>> m;
    for (size_t i = 0; i < rows.size(); ++i) m[integer(i, "frame")].push_back(i);
    return m;
  }
};

/// Parses CSV text; every row must have as many fields as the header.
Table parse_csv(const std::string& text) {
  Table t;
  const auto lines = split_lines(text);
  if (lines.empty()) {
    ADD_FAILURE() << "empty CSV";
    return t;
  }
  t.columns = split(lines[0], ',');
  for (size_t i = 1; i < lines.size(); ++i) {
    auto f = split(lines[i], ',');
    EXPECT_EQ(f.size(), t.columns.size()) << "CSV line " << i + 1 << ": " << lines[i];
    t.rows.push_back(std::move(f));
  }
  EXPECT_TRUE(text.empty() || text.back() == '\n') << "the CSV does not end with a newline";
  return t;
}

/// Checks a table of the moving scene (or part of it): frames in increasing order, blob numbers
/// 0..n-1 within a frame, blobs in raster order of their first pixel, centroid within `tolerance`
/// of the disk centres; with `exact`, area, bounding box and weighted centroid exactly too.
void expect_scene_rows(const Table& t, const std::set<std::int64_t>& frames, double tolerance, bool exact) {
  const auto groups = t.by_frame();
  std::set<std::int64_t> seen;
  for (const auto& [f, idx] : groups) seen.insert(f);
  EXPECT_EQ(seen, frames);
  std::int64_t last_frame = -1;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const auto f = t.integer(i, "frame");
    EXPECT_GE(f, last_frame) << "frames out of order at row " << i;
    last_frame = f;
  }
  for (const auto& [f, idx] : groups) {
    const auto expected = expected_blobs(scene(static_cast<int>(f)));
    ASSERT_EQ(idx.size(), expected.size()) << "frame " << f << ": one row per disk";
    for (size_t b = 0; b < idx.size(); ++b) {
      const size_t r = idx[b];
      const auto& e = expected[b];
      SCOPED_TRACE("frame " + std::to_string(f) + " blob " + std::to_string(b));
      EXPECT_EQ(t.integer(r, "blob"), static_cast<std::int64_t>(b));
      EXPECT_NEAR(t.num(r, "cx"), e.cx, tolerance);
      EXPECT_NEAR(t.num(r, "cy"), e.cy, tolerance);
      EXPECT_NEAR(t.num(r, "wcx"), e.cx, tolerance);
      EXPECT_NEAR(t.num(r, "wcy"), e.cy, tolerance);
      if (exact) {
        EXPECT_EQ(t.integer(r, "area"), e.area);
        EXPECT_EQ(t.integer(r, "x0"), e.box.x);
        EXPECT_EQ(t.integer(r, "y0"), e.box.y);
        EXPECT_EQ(t.integer(r, "w"), e.box.width);
        EXPECT_EQ(t.integer(r, "h"), e.box.height);
      }
    }
  }
}

/// The rows of frames 0..n-1.
Table only_frames(const Table& t, std::int64_t n) {
  Table out;
  out.columns = t.columns;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    if (t.integer(i, "frame") < n) out.rows.push_back(t.rows[i]);
  }
  return out;
}

std::set<std::int64_t> range_set(std::int64_t n) {
  std::set<std::int64_t> s;
  for (std::int64_t i = 0; i < n; ++i) s.insert(i);
  return s;
}

struct Summary {
  std::int64_t processed = -1, dropped = -1, blobs = -1;
};

/// Parses "N frames, D dropped, B blobs in S s (F frames/s); latency p50 X ms, p99 Y ms".
std::optional<Summary> parse_summary(const std::string& err) {
  static const std::regex re(
      R"((\d+) frames, (\d+) dropped, (\d+) blobs in [0-9.]+ s \([0-9.]+ frames/s\); latency p50 [0-9.]+ ms, p99 [0-9.]+ ms)");
  std::smatch m;
  if (!std::regex_search(err, m, re)) return std::nullopt;
  return Summary{std::stoll(m[1]), std::stoll(m[2]), std::stoll(m[3])};
}

/// "path:line:col: " at the start of the message after "error: "; returns {line, col}.
std::optional<std::pair<int, int>> graph_error_position(const std::string& error_line, const std::string& path) {
  const std::string prefix = "error: " + path + ":";
  const auto at = error_line.find(prefix);
  if (at == std::string::npos) return std::nullopt;
  static const std::regex re(R"(^(\d+):(\d+): )");
  std::smatch m;
  const std::string rest = error_line.substr(at + prefix.size());
  if (!std::regex_search(rest, m, re)) return std::nullopt;
  return std::make_pair(std::stoi(m[1]), std::stoi(m[2]));
}

// ---------------------------------------------------------------------------------------------
// Inputs, generated once per test program in a fresh temp directory

void write_video(const fs::path& path, int fourcc, int frames) {
  cv::VideoWriter w(path.string(), cv::CAP_FFMPEG, fourcc, 25.0, cv::Size(kW, kH), true);
  ASSERT_TRUE(w.isOpened()) << "cannot write the test video " << path;
  for (int k = 0; k < frames; ++k) w.write(render(scene(k)));
  w.release();
}

class Cli : public ::testing::Test {
 protected:
  static inline fs::path root;
  static inline fs::path mkv;       // FFV1, lossless, kFrames frames
  static inline fs::path avi;       // MJPG, kFrames frames
  static inline fs::path png_dir;   // kFrames PNGs of the scene, plus a text file to ignore
  static inline fs::path examples;  // NEOPIPE_EXAMPLES_DIR

  static void SetUpTestSuite() {
    std::string tmpl = (fs::temp_directory_path() / "neopipe_cli_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr) << tmpl << ": " << std::strerror(errno);
    root = tmpl;
    examples = NEOPIPE_EXAMPLES_DIR;
    mkv = root / "scene.mkv";
    avi = root / "scene.avi";
    write_video(mkv, cv::VideoWriter::fourcc('F', 'F', 'V', '1'), kFrames);
    write_video(avi, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), kFrames);
    png_dir = root / "scene_png";
    fs::create_directory(png_dir);
    for (int k = 0; k < kFrames; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "f%03d.png", k);
      cv::imwrite((png_dir / name).string(), render(scene(k)));
    }
    write_text(png_dir / "notes.txt", "not an image\n");
  }

  static void TearDownTestSuite() {
    if (std::getenv("NEOPIPE_CLI_KEEP_TMP") != nullptr) {
      std::printf("NEOPIPE_CLI_KEEP_TMP: inputs and outputs kept in %s\n", root.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(root, ec);
  }

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = root / info->name();
    fs::create_directories(dir);
  }

  /// `neopipe run ARGS... --out dir/NAME`, expected to succeed; returns the table file's text.
  std::string run_to_file(std::vector<std::string> args, const std::string& name = "t.csv") {
    const fs::path out = dir / name;
    args.insert(args.begin(), "run");
    args.push_back("--out");
    args.push_back(out.string());
    const RunResult r = run_neopipe(args);
    EXPECT_TRUE(succeeded(r)) << describe(args);
    return slurp(out);
  }

  static std::string png(int k) {
    char name[32];
    std::snprintf(name, sizeof name, "f%03d.png", k);
    return (png_dir / name).string();
  }

  fs::path dir;  // this test's own directory
};

// ---------------------------------------------------------------------------------------------
// 0. The generated inputs are what the tests assume (otherwise the tool would be blamed wrongly)

TEST_F(Cli, GeneratedLosslessVideoDecodesToTheDrawnFrames) {
  cv::VideoCapture cap(mkv.string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(cap.isOpened());
  int k = 0;
  cv::Mat f;
  while (cap.read(f)) {
    ASSERT_LT(k, kFrames);
    EXPECT_EQ(cv::norm(f, render(scene(k)), cv::NORM_INF), 0) << "FFV1 frame " << k << " is not lossless";
    ++k;
  }
  EXPECT_EQ(k, kFrames);
}

// ---------------------------------------------------------------------------------------------
// 1. The blob table

TEST_F(Cli, RunVideoWritesCsvWithOneRowPerDiskAndExactCentroids) {
  const fs::path out = dir / "t.csv";
  const RunResult r = run_neopipe({"run", mkv.string(), "--out", out.string()});
  ASSERT_TRUE(succeeded(r));
  EXPECT_EQ(r.out, "") << "with --out nothing goes to stdout";
  const std::string text = slurp(out);
  ASSERT_EQ(split_lines(text).at(0), kHeader);
  const Table t = parse_csv(text);
  EXPECT_EQ(t.rows.size(), static_cast<size_t>(3 * kFrames));
  expect_scene_rows(t, range_set(kFrames), 0.5, true);
  // Exact too: a filled disk is symmetric about its integer centre.
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const double cx = t.num(i, "cx");
    EXPECT_EQ(cx, std::round(cx)) << "row " << i;
  }
}

TEST_F(Cli, RunSummaryOnStderrReportsFramesRateLatencyAndDrops) {
  const RunResult r = run_neopipe({"run", mkv.string(), "--out", (dir / "t.csv").string()});
  ASSERT_TRUE(succeeded(r));
  const auto s = parse_summary(r.err);
  ASSERT_TRUE(s) << "no summary in stderr:\n" << r.err;
  EXPECT_EQ(s->processed, kFrames);
  EXPECT_EQ(s->dropped, 0);
  EXPECT_EQ(s->blobs, 3 * kFrames);
  EXPECT_TRUE(contains(r.err, mkv.string())) << "the summary names the input:\n" << r.err;
  EXPECT_FALSE(contains(lower(r.err), "error")) << r.err;
}

TEST_F(Cli, QuietRunPrintsNothingOnStderr) {
  const RunResult r = run_neopipe({"run", mkv.string(), "-q", "--out", (dir / "t.csv").string()});
  ASSERT_TRUE(succeeded(r));
  EXPECT_EQ(r.err, "");
}

TEST_F(Cli, WithoutOutTheTableGoesToStdout) {
  const std::string file = run_to_file({mkv.string()});
  const RunResult r = run_neopipe({"run", mkv.string()});
  ASSERT_TRUE(succeeded(r));
  EXPECT_EQ(r.out, file);
  ASSERT_FALSE(r.out.empty());
  EXPECT_EQ(split_lines(r.out).at(0), kHeader);
}

TEST_F(Cli, JsonLinesHoldTheSameFieldsAndValuesAsCsv) {
  const Table csv = parse_csv(run_to_file({mkv.string()}));
  const std::string jsonl = run_to_file({mkv.string()}, "t.jsonl");
  const RunResult by_flag = run_neopipe({"run", mkv.string(), "--format", "jsonl"});
  ASSERT_TRUE(succeeded(by_flag));
  EXPECT_EQ(by_flag.out, jsonl) << "--format jsonl on stdout == --out t.jsonl";

  const auto lines = split_lines(jsonl);
  ASSERT_EQ(lines.size(), csv.rows.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    json j;
    ASSERT_NO_THROW(j = json::parse(lines[i])) << "line " << i + 1 << ": " << lines[i];
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j.size(), csv.columns.size()) << lines[i];
    for (const auto& c : csv.columns) {
      ASSERT_TRUE(j.contains(c)) << "line " << i + 1 << " lacks " << c;
      ASSERT_TRUE(j[c].is_number()) << c;
      EXPECT_EQ(j[c].get<double>(), csv.num(i, c)) << "line " << i + 1 << " field " << c;
    }
  }
}

TEST_F(Cli, MomentsAddsTheSecondCentralMoments) {
  const std::string text = run_to_file({mkv.string(), "--moments"});
  ASSERT_EQ(split_lines(text).at(0), kHeader + ",mu20,mu11,mu02");
  const Table t = parse_csv(text);
  expect_scene_rows(t, range_set(kFrames), 0.5, true);
  for (const auto& [f, idx] : t.by_frame()) {
    const auto e = expected_blobs(scene(static_cast<int>(f)));
    ASSERT_EQ(idx.size(), e.size());
    for (size_t b = 0; b < idx.size(); ++b) {
      EXPECT_NEAR(t.num(idx[b], "mu20"), e[b].mu20, 1e-6 * e[b].mu20) << "frame " << f << " blob " << b;
      EXPECT_NEAR(t.num(idx[b], "mu11"), e[b].mu11, 1e-6 * e[b].mu20) << "frame " << f << " blob " << b;
      EXPECT_NEAR(t.num(idx[b], "mu02"), e[b].mu02, 1e-6 * e[b].mu02) << "frame " << f << " blob " << b;
    }
  }
  const std::string jsonl = run_to_file({mkv.string(), "--moments"}, "t.jsonl");
  const json first = json::parse(split_lines(jsonl).at(0));
  for (const char* k : {"mu20", "mu11", "mu02"}) EXPECT_TRUE(first.contains(k)) << k;
}

TEST_F(Cli, FixedThresholdIsHonouredAndStrict) {
  // Squares of gray 128, 129 and 200 on black: foreground is value > T.
  cv::Mat img = cv::Mat::zeros(60, 90, CV_8UC3);
  img(cv::Rect(5, 5, 10, 10)).setTo(cv::Scalar::all(128));
  img(cv::Rect(35, 5, 10, 10)).setTo(cv::Scalar::all(129));
  img(cv::Rect(65, 5, 10, 10)).setTo(cv::Scalar::all(200));
  const fs::path p = dir / "levels.png";
  cv::imwrite(p.string(), img);
  const auto count_and_first_x = [&](const std::string& t) {
    const Table tab = parse_csv(run_to_file({p.string(), "--threshold", t}));
    return std::make_pair(tab.rows.size(), tab.rows.empty() ? -1 : tab.integer(0, "x0"));
  };
  EXPECT_EQ(count_and_first_x("127"), std::make_pair(size_t{3}, std::int64_t{5}));
  EXPECT_EQ(count_and_first_x("128"), std::make_pair(size_t{2}, std::int64_t{35}));
  EXPECT_EQ(count_and_first_x("199"), std::make_pair(size_t{1}, std::int64_t{65}));
  EXPECT_EQ(count_and_first_x("200"), std::make_pair(size_t{0}, std::int64_t{-1}));
}

TEST_F(Cli, ConnectivityFourSplitsDiagonalNeighbours) {
  // Two 10x10 squares touching only corner to corner: one 8-connected blob, two 4-connected ones.
  cv::Mat img = cv::Mat::zeros(60, 60, CV_8UC3);
  img(cv::Rect(10, 10, 10, 10)).setTo(cv::Scalar::all(255));
  img(cv::Rect(20, 20, 10, 10)).setTo(cv::Scalar::all(255));
  const fs::path p = dir / "diagonal.png";
  cv::imwrite(p.string(), img);
  const Table four = parse_csv(run_to_file({p.string(), "--connectivity", "4"}));
  ASSERT_EQ(four.rows.size(), 2u);
  EXPECT_EQ(four.integer(0, "area"), 100);
  EXPECT_EQ(four.integer(1, "area"), 100);
  EXPECT_EQ(four.integer(1, "x0"), 20);
  const Table eight = parse_csv(run_to_file({p.string(), "--connectivity", "8"}));
  ASSERT_EQ(eight.rows.size(), 1u);
  EXPECT_EQ(eight.integer(0, "area"), 200);
  EXPECT_EQ(eight.integer(0, "w"), 20);
  const Table dflt = parse_csv(run_to_file({p.string()}));
  EXPECT_EQ(dflt.rows.size(), 1u) << "the default is 8-connected";
}

TEST_F(Cli, SinglePngIsOneFrame) {
  const Table t = parse_csv(run_to_file({png(7)}));
  ASSERT_EQ(t.rows.size(), 3u);
  for (size_t i = 0; i < t.rows.size(); ++i) EXPECT_EQ(t.integer(i, "frame"), 0);
  // Frame 0 of the table is scene frame 7.
  const auto e = expected_blobs(scene(7));
  for (size_t b = 0; b < 3; ++b) {
    EXPECT_NEAR(t.num(b, "cx"), e[b].cx, 1e-9);
    EXPECT_NEAR(t.num(b, "cy"), e[b].cy, 1e-9);
    EXPECT_EQ(t.integer(b, "area"), e[b].area);
  }
}

TEST_F(Cli, SeveralPngsAreFramesInTheGivenOrder) {
  // Given as f004 f001 f002: table frame 0 must be scene frame 4, and so on.
  const std::vector<int> order{4, 1, 2};
  const Table t = parse_csv(run_to_file({png(4), png(1), png(2)}));
  const auto groups = t.by_frame();
  ASSERT_EQ(groups.size(), order.size());
  for (size_t f = 0; f < order.size(); ++f) {
    ASSERT_TRUE(groups.count(static_cast<std::int64_t>(f))) << "frame " << f;
    const auto& idx = groups.at(static_cast<std::int64_t>(f));
    const auto e = expected_blobs(scene(order[f]));
    ASSERT_EQ(idx.size(), e.size());
    for (size_t b = 0; b < idx.size(); ++b) {
      EXPECT_NEAR(t.num(idx[b], "cx"), e[b].cx, 1e-9) << "frame " << f;
      EXPECT_NEAR(t.num(idx[b], "cy"), e[b].cy, 1e-9) << "frame " << f;
    }
  }
}

TEST_F(Cli, DirectoryOfImagesIsReadInNameOrderIgnoringOtherFiles) {
  const std::string text = run_to_file({png_dir.string()});
  const Table t = parse_csv(text);
  EXPECT_EQ(t.rows.size(), static_cast<size_t>(3 * kFrames));
  expect_scene_rows(t, range_set(kFrames), 1e-9, true);
  // The same as the lossless video, byte for byte.
  EXPECT_EQ(text, run_to_file({mkv.string()}, "video.csv"));
}

// ---------------------------------------------------------------------------------------------
// 2, 3. Determinism and the example graph

TEST_F(Cli, BuiltInGraphGivesIdenticalBytesForAnyThreadCount) {
  const std::string one = run_to_file({mkv.string(), "--threads", "1"}, "t1.csv");
  ASSERT_EQ(parse_csv(one).rows.size(), static_cast<size_t>(3 * kFrames));
  EXPECT_EQ(run_to_file({mkv.string(), "--threads", "2"}, "t2.csv"), one);
  EXPECT_EQ(run_to_file({mkv.string(), "--threads", "8"}, "t8.csv"), one);
  EXPECT_EQ(run_to_file({mkv.string(), "--threads", "8", "--frames-in-flight", "2"}, "t8b.csv"), one);
}

TEST_F(Cli, BackgroundSubtractionGraphGivesIdenticalBytesForAnyThreadCount) {
  const std::string graph = (examples / "background_subtraction.yaml").string();
  const std::string one = run_to_file({avi.string(), "--graph", graph, "--threads", "1"}, "t1.csv");
  // The moving disks differ from the running background, so there is something to compare.
  EXPECT_GT(parse_csv(one).rows.size(), static_cast<size_t>(kFrames));
  EXPECT_EQ(run_to_file({avi.string(), "--graph", graph, "--threads", "2"}, "t2.csv"), one);
  EXPECT_EQ(run_to_file({avi.string(), "--graph", graph, "--threads", "8"}, "t8.csv"), one);
}

// examples/blobs.yaml reads BGR and converts in the graph, as the built-in graph does with --annotate
// (which draws on colour frames); without it, the built-in graph reads gray, from a YUV video its
// luma plane, which can differ from BT.601 of the decoded BGR by a few levels. So: byte for byte
// the same as the built-in graph with --annotate on any video, and without it on the FFV1 video
// (RGB pixels, read through BGR either way); on the MJPG video the same blobs, centroids within
// 0.01 pixel.
TEST_F(Cli, BlobsExampleGraphEqualsTheBuiltInGraph) {
  const std::string yaml = (examples / "blobs.yaml").string();
  const std::string annotated =
      run_to_file({avi.string(), "--annotate", (dir / "a.avi").string()}, "builtin_annotated.csv");
  EXPECT_EQ(parse_csv(annotated).rows.size(), static_cast<size_t>(3 * kFrames));
  EXPECT_EQ(run_to_file({avi.string(), "--graph", yaml}, "yaml.csv"), annotated);
  EXPECT_EQ(run_to_file({avi.string(), "--graph", yaml, "--moments"}, "yaml_m.csv"),
            run_to_file({avi.string(), "--moments", "--annotate", (dir / "b.avi").string()}, "builtin_m.csv"));
  EXPECT_EQ(run_to_file({mkv.string(), "--graph", yaml}, "yaml_mkv.csv"), run_to_file({mkv.string()}, "mkv.csv"));

  const Table luma = parse_csv(run_to_file({avi.string()}, "builtin.csv"));
  const Table bgr = parse_csv(annotated);
  ASSERT_EQ(luma.rows.size(), bgr.rows.size());
  for (size_t i = 0; i < luma.rows.size(); ++i) {
    for (const char* c : {"frame", "blob", "x0", "y0", "w", "h"}) EXPECT_EQ(luma.integer(i, c), bgr.integer(i, c)) << c;
    for (const char* c : {"cx", "cy", "wcx", "wcy"}) EXPECT_NEAR(luma.num(i, c), bgr.num(i, c), 0.01) << c;
  }
}

TEST_F(Cli, MjpgVideoCentroidsAreCloseToTheDiskCentres) {
  const Table t = parse_csv(run_to_file({avi.string()}));
  expect_scene_rows(t, range_set(kFrames), 0.5, false);
}

// ---------------------------------------------------------------------------------------------
// 4. Annotation

TEST_F(Cli, AnnotateVideoHasEveryFrame) {
  const fs::path video = dir / "out.mp4";
  const RunResult r =
      run_neopipe({"run", mkv.string(), "--annotate", video.string(), "--out", (dir / "t.csv").string()});
  ASSERT_TRUE(succeeded(r));
  cv::VideoCapture cap(video.string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(cap.isOpened()) << video;
  int n = 0;
  cv::Mat f;
  while (cap.read(f)) {
    EXPECT_EQ(f.size(), cv::Size(kW, kH));
    ++n;
  }
  EXPECT_EQ(n, kFrames);
}

TEST_F(Cli, AnnotateSingleImageWritesExactlyThatPng) {
  const fs::path out = dir / "out.png";
  const std::string text = run_to_file({png(3), "--annotate", out.string()});
  ASSERT_TRUE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "out_000000.png"));
  const cv::Mat img = cv::imread(out.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.size(), cv::Size(kW, kH));
  // The bounding box is drawn in green: its top-left corner (outside the disk) is green.
  const Table t = parse_csv(text);
  ASSERT_EQ(t.rows.size(), 3u);
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const auto x0 = static_cast<int>(t.integer(i, "x0"));
    const auto y0 = static_cast<int>(t.integer(i, "y0"));
    EXPECT_EQ(img.at<cv::Vec3b>(y0, x0), cv::Vec3b(0, 200, 0)) << "blob " << i;
  }
}

TEST_F(Cli, AnnotateSeveralFramesWritesNumberedPngs) {
  const fs::path out = dir / "out.png";
  run_to_file({png(0), png(1), png(2), png(3), png(4), "--annotate", out.string()});
  for (int k = 0; k < 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "out_%06d.png", k);
    const cv::Mat img = cv::imread((dir / name).string(), cv::IMREAD_COLOR);
    EXPECT_FALSE(img.empty()) << name;
    EXPECT_EQ(img.size(), cv::Size(kW, kH)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "out_000005.png"));
  EXPECT_FALSE(fs::exists(out)) << "several frames go to numbered files, not to out.png";
}

// ---------------------------------------------------------------------------------------------
// 5. Real time

TEST_F(Cli, RealtimeAccountsForEveryFrameAsProcessedOrDropped) {
  const fs::path out = dir / "t.csv";
  const RunResult r =
      run_neopipe({"run", mkv.string(), "--realtime", "--fps", "1000", "--threads", "2", "--out", out.string()});
  ASSERT_TRUE(succeeded(r));
  const auto s = parse_summary(r.err);
  ASSERT_TRUE(s) << "no summary with a dropped count in stderr:\n" << r.err;
  EXPECT_EQ(s->processed + s->dropped, kFrames);
  EXPECT_GT(s->processed, 0);
  const Table t = parse_csv(slurp(out));
  EXPECT_EQ(t.rows.size(), static_cast<size_t>(3 * s->processed));
  EXPECT_EQ(s->blobs, static_cast<std::int64_t>(t.rows.size()));
  // Rows carry the source frame numbers of the processed frames, and their contents match.
  std::set<std::int64_t> frames;
  for (const auto& [f, idx] : t.by_frame()) frames.insert(f);
  EXPECT_EQ(static_cast<std::int64_t>(frames.size()), s->processed);
  for (const auto f : frames) {
    EXPECT_GE(f, 0);
    EXPECT_LT(f, kFrames);
  }
  expect_scene_rows(t, frames, 0.5, true);
}

/// The sink of `neopipe run --annotate STEM.png`, made to block: the annotated PNG of every frame k
/// goes into a FIFO, STEM_kkkkkk.png, read here. Each is opened at once (without waiting for a writer)
/// and shrunk to a page, so the child's write of a larger PNG blocks until the FIFO is read.
class BlockingPngSink {
 public:
  BlockingPngSink(const fs::path& dir, const std::string& stem, int frames) : bytes_(static_cast<size_t>(frames)) {
    for (int k = 0; k < frames; ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "%s_%06d.png", stem.c_str(), k);
      const fs::path fifo = dir / name;
      int fd = -1;
      if (mkfifo(fifo.c_str(), 0600) != 0) {
        ADD_FAILURE() << "mkfifo " << fifo << ": " << std::strerror(errno);
      } else if ((fd = open(fifo.c_str(), O_RDONLY | O_NONBLOCK)) < 0) {
        ADD_FAILURE() << "open " << fifo << ": " << std::strerror(errno);
      } else {
        (void)fcntl(fd, F_SETPIPE_SZ, 4096);  // the smallest pipe; a failure only leaves 64 KiB
      }
      fds_.push_back(fd);
    }
  }
  ~BlockingPngSink() {
    for (const int fd : fds_) {
      if (fd >= 0) close(fd);
    }
  }
  BlockingPngSink(const BlockingPngSink&) = delete;
  BlockingPngSink& operator=(const BlockingPngSink&) = delete;

  /// The first frame whose PNG the child began to write (the child is then inside its sink, on that
  /// frame, and stays there); nullopt if the child ended first (the test fails rather than hangs).
  std::optional<int> wait_for_the_first_writer(const std::atomic<bool>& child_ended) {
    while (!child_ended) {
      for (size_t k = 0; k < fds_.size(); ++k) {
        if (fds_[k] < 0) continue;
        pollfd p{fds_[k], POLLIN, 0};
        // Before any writer, Linux reports nothing (or a hang-up) on a FIFO: look again later.
        if (poll(&p, 1, 0) > 0 && (p.revents & POLLIN) != 0) return static_cast<int>(k);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return std::nullopt;
  }

  /// Reads whatever the child writes, letting it go on, until it has ended.
  void drain(const std::atomic<bool>& child_ended) {
    for (;;) {
      const bool last_sweep = child_ended;  // read after the end once more: nothing is left behind
      for (size_t k = 0; k < fds_.size(); ++k) {
        if (fds_[k] < 0) continue;
        char buf[65536];
        ssize_t n = 0;
        while ((n = read(fds_[k], buf, sizeof buf)) > 0) bytes_[k].append(buf, static_cast<size_t>(n));
      }
      if (last_sweep) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  /// The bytes written into frame k's FIFO.
  const std::string& bytes(int k) const { return bytes_[static_cast<size_t>(k)]; }

 private:
  std::vector<int> fds_;
  std::vector<std::string> bytes_;
};

TEST_F(Cli, RealtimeDropsFramesWhileTheSinkIsBlocked) {
  // 20 frames of noise at --fps 1000 (due within 20 ms); the annotated PNGs go into FIFOs, and the
  // first one written is not read until a second after the child began writing it, so the driver,
  // which runs the sink, takes no frame for that second. The reader goes on at the pace: with at
  // most two frames in the pipeline and one waiting to be handed over, frames are dropped unless
  // the child's reader thread could not read two frames in that whole second. No time is asserted:
  // the second is a thousand frame periods. Noise, so that a PNG (about 230 KB) cannot fit a FIFO;
  // the threshold above the noise, so that the blob table stays empty.
  const fs::path video = dir / "noise.mkv";
  {
    cv::VideoWriter w(video.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('F', 'F', 'V', '1'), 25.0,
                      cv::Size(320, 240), true);
    ASSERT_TRUE(w.isOpened());
    cv::RNG rng(18);
    cv::Mat f(240, 320, CV_8UC3);
    for (int k = 0; k < kFrames; ++k) {
      rng.fill(f, cv::RNG::UNIFORM, 0, 150);
      w.write(f);
    }
  }
  BlockingPngSink sink(dir, "a", kFrames);
  std::optional<int> first;
  std::atomic<bool> child_ended{false};
  std::thread reader([&] {
    first = sink.wait_for_the_first_writer(child_ended);
    if (first) std::this_thread::sleep_for(std::chrono::seconds(1));
    sink.drain(child_ended);
  });
  const RunResult r =
      run_neopipe({"run", video.string(), "--realtime", "--fps", "1000", "--threads", "2", "--frames-in-flight", "2",
                   "--threshold", "250", "--annotate", (dir / "a.png").string(), "--out", (dir / "t.csv").string()});
  child_ended = true;
  reader.join();
  ASSERT_TRUE(first.has_value()) << "the child wrote no annotated image\n" << r.err;
  ASSERT_TRUE(succeeded(r));
  const auto s = parse_summary(r.err);
  ASSERT_TRUE(s) << r.err;
  EXPECT_EQ(s->processed + s->dropped, kFrames);
  EXPECT_GE(s->processed, 1);
  EXPECT_GE(s->dropped, 1) << r.err;
  // Every processed frame, and only those, wrote its annotated PNG.
  int written = 0;
  for (int k = 0; k < kFrames; ++k) {
    const std::string& b = sink.bytes(k);
    if (b.empty()) continue;
    ++written;
    EXPECT_FALSE(cv::imdecode(std::vector<uchar>(b.begin(), b.end()), cv::IMREAD_COLOR).empty())
        << "frame " << k << "'s annotated image, " << b.size() << " bytes, is no PNG";
  }
  EXPECT_EQ(written, s->processed);
  // The lag is reported, and no larger than the run.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"(blobs in ([0-9.]+) s .*reader lag max ([0-9.]+) ms)")))
      << r.err;
  EXPECT_LE(std::stod(m[2]), 1e3 * std::stod(m[1]) + 1);  // both rounded: 1 ms for the seconds' three decimals
}

// ---------------------------------------------------------------------------------------------
// 6. Bad input

TEST_F(Cli, MissingFileIsAnError) {
  const std::string missing = (dir / "missing.mp4").string();
  const RunResult r = run_neopipe({"run", missing, "--out", (dir / "t.csv").string()});
  expect_one_error(r, {missing, "no such file"}, 1);
}

TEST_F(Cli, UnreadableFileIsAnError) {
  if (geteuid() == 0) GTEST_SKIP() << "running as root, which can read a chmod 000 file";
  const fs::path p = dir / "locked.png";
  cv::imwrite(p.string(), render(scene(0)));
  ASSERT_EQ(chmod(p.c_str(), 0), 0);
  const RunResult r = run_neopipe({"run", p.string(), "--out", (dir / "t.csv").string()});
  chmod(p.c_str(), 0644);
  expect_one_error(r, {p.string(), "cannot open", "ermission"}, 1);
}

TEST_F(Cli, TextFileNamedPngIsAnError) {
  const fs::path p = dir / "fake.png";
  write_text(p, "this is plain text, not a PNG\n");
  const RunResult r = run_neopipe({"run", p.string(), "--out", (dir / "t.csv").string()});
  // An image's name with content no image reader recognises is reported as a bad image, not
  // handed to FFmpeg as a video.
  expect_one_error(r, {p.string(), "not an image OpenCV can read"}, 1);
}

TEST_F(Cli, TextFileNamedMp4IsAnError) {
  const fs::path p = dir / "fake.mp4";
  write_text(p, "this is plain text, not an MP4 video\n");
  const RunResult r = run_neopipe({"run", p.string(), "--out", (dir / "t.csv").string()});
  expect_one_error(r, {p.string(), "neither an image nor a video"}, 1);
}

TEST_F(Cli, EmptyDirectoryIsAnError) {
  const fs::path p = dir / "empty_dir";
  fs::create_directory(p);
  const RunResult r = run_neopipe({"run", p.string(), "--out", (dir / "t.csv").string()});
  expect_one_error(r, {p.string(), "no image files"}, 1);
}

TEST_F(Cli, ZeroLengthAviIsAnError) {
  const fs::path p = dir / "zero.avi";
  write_text(p, "");
  const RunResult r = run_neopipe({"run", p.string(), "--out", (dir / "t.csv").string()});
  expect_one_error(r, {p.string(), "neither an image nor a video"}, 1);
}

TEST_F(Cli, TruncatedVideoFailsAfterWritingTheDecodedFrames) {
  constexpr int kLong = 30;
  const fs::path p = dir / "cut.avi";
  write_video(p, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), kLong);
  const auto full = fs::file_size(p);
  fs::resize_file(p, full * 6 / 10);
  const fs::path out = dir / "t.csv";
  const RunResult r = run_neopipe({"run", p.string(), "--threads", "2", "--out", out.string()});
  const std::string line = expect_one_error(r, {p.string(), "truncated"}, 1);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(stopped at frame (\d+) of (\d+))"))) << line;
  const int decoded = std::stoi(m[1]);
  EXPECT_EQ(std::stoi(m[2]), kLong);
  EXPECT_GT(decoded, 0);
  EXPECT_LT(decoded, kLong);
  // Every frame decoded before the failure has its rows in the table. The last of them is the one
  // cut by the truncation, which FFmpeg's error concealment hands over half decoded, so only its
  // presence is checked; the frames before it must be right.
  const Table t = parse_csv(slurp(out));
  ASSERT_EQ(t.columns, split(kHeader, ','));
  std::set<std::int64_t> present;
  for (const auto& [f, idx] : t.by_frame()) present.insert(f);
  EXPECT_EQ(present, range_set(decoded));
  expect_scene_rows(only_frames(t, decoded - 1), range_set(decoded - 1), 0.5, false);
  const auto s = parse_summary(r.err);
  ASSERT_TRUE(s) << r.err;
  EXPECT_EQ(s->processed, decoded);
}

// OpenCV's imgcodecs and videoio (and the ~240 libraries they bring) live in the media plug-in,
// loaded only by what reads or writes images or writes videos (pipeline/media/media.hpp).
TEST_F(Cli, VideoRunLoadsNoOpenCvCodecsAnImageRunDoes) {
  // The dynamic loader names every library it loads on stderr.
  ASSERT_EQ(setenv("LD_DEBUG", "files", 1), 0);
  const RunResult video = run_neopipe({"run", mkv.string(), "-q", "--out", (dir / "v.csv").string()});
  const RunResult image = run_neopipe({"run", png(0), "-q", "--out", (dir / "i.csv").string()});
  unsetenv("LD_DEBUG");
  ASSERT_EQ(video.exit_code, 0) << video.err.substr(0, 2000);
  ASSERT_EQ(image.exit_code, 0) << image.err.substr(0, 2000);
  EXPECT_TRUE(contains(video.err, "libavcodec")) << "LD_DEBUG=files printed no library names";
  for (const char* lib : {"libneopipe_media", "libopencv_imgcodecs", "libopencv_videoio"}) {
    EXPECT_FALSE(contains(video.err, lib)) << lib << " loaded for a video run";
    EXPECT_TRUE(contains(image.err, lib)) << lib << " not loaded for an image run";
  }
  for (const char* table : {"v.csv", "i.csv"}) {
    const auto lines = split_lines(slurp(dir / table));
    ASSERT_GT(lines.size(), 1U) << table;
    EXPECT_EQ(lines.front(), kHeader) << table;
  }
}

TEST_F(Cli, ImageOfAnotherSizeMidSequenceFailsAfterWritingTheFirstFrames) {
  const fs::path seq = dir / "seq";
  fs::create_directory(seq);
  cv::imwrite((seq / "a0.png").string(), render(scene(0)));
  cv::imwrite((seq / "a1.png").string(), render(scene(1)));
  cv::imwrite((seq / "a2.png").string(), render(scene(2), cv::Size(kW + 8, kH)));
  cv::imwrite((seq / "a3.png").string(), render(scene(3)));
  const fs::path out = dir / "t.csv";
  const fs::path third = seq / "a2.png";
  const RunResult r = run_neopipe({"run", seq.string(), "--threads", "2", "--out", out.string()});
  expect_one_error(r, {third.string(), "168x120", "160x120"}, 1);
  const Table t = parse_csv(slurp(out));
  expect_scene_rows(t, {0, 1}, 1e-9, true);
}

// Graph specs with mistakes on known lines.
const char* const kUnknownKernel =
    "name: unknown_kernel\n"        // 1
    "nodes:\n"                      // 2
    "  - name: src\n"               // 3
    "    kernel: source\n"          // 4
    "    params: {format: bgr}\n"   // 5
    "  - name: gray\n"              // 6
    "    kernel: grey\n"            // 7  <- col 13
    "    inputs: {in: src}\n"       // 8
    "  - name: blobs\n"             // 9
    "    kernel: blobs\n"           // 10
    "    params: {threshold: 0}\n"  // 11
    "    inputs: {in: gray}\n"      // 12
    "outputs: [blobs]\n";           // 13

const char* const kYamlSyntax =
    "name: bad_yaml\n"             // 1
    "nodes:\n"                     // 2
    "  - name: src\n"              // 3
    "    kernel: source\n"         // 4
    "    params: {format: bgr}\n"  // 5
    "  - name: gray\n"             // 6
    "    kernel: gray: gray\n"     // 7  <- a second ':' on one line
    "    inputs: {in: src}\n"      // 8
    "outputs: [gray]\n";           // 9

const char* const kCycle =
    "name: cycle\n"                 // 1
    "nodes:\n"                      // 2
    "  - name: src\n"               // 3
    "    kernel: source\n"          // 4
    "    params: {format: gray}\n"  // 5
    "  - name: a\n"                 // 6
    "    kernel: absdiff\n"         // 7
    "    inputs:\n"                 // 8
    "      a: src\n"                // 9
    "      b: c\n"                  // 10 <- from c, no delay
    "  - name: c\n"                 // 11
    "    kernel: absdiff\n"         // 12
    "    inputs:\n"                 // 13
    "      a: a\n"                  // 14 <- from a, no delay
    "      b: src\n"                // 15
    "  - name: blobs\n"             // 16
    "    kernel: blobs\n"           // 17
    "    params: {threshold: 0}\n"  // 18
    "    inputs: {in: c}\n"         // 19
    "outputs: [blobs]\n";           // 20

const char* const kSelfLoop =
    "name: self_loop\n"             // 1
    "nodes:\n"                      // 2
    "  - name: src\n"               // 3
    "    kernel: source\n"          // 4
    "    params: {format: gray}\n"  // 5
    "  - name: a\n"                 // 6
    "    kernel: absdiff\n"         // 7
    "    inputs:\n"                 // 8
    "      a: src\n"                // 9
    "      b: a\n"                  // 10 <- itself, no delay
    "  - name: blobs\n"             // 11
    "    kernel: blobs\n"           // 12
    "    params: {threshold: 0}\n"  // 13
    "    inputs: {in: a}\n"         // 14
    "outputs: [blobs]\n";           // 15

const char* const kNoBlobs =
    "name: no_blobs\n"
    "nodes:\n"
    "  - name: src\n"
    "    kernel: source\n"
    "    params: {format: gray}\n"
    "  - name: binary\n"
    "    kernel: threshold\n"
    "    params: {value: 128}\n"
    "    inputs: {in: src}\n"
    "outputs: [binary]\n";

class CliGraph : public Cli {
 protected:
  /// Runs the lossless video through a graph spec with `text`; returns the checked error line.
  std::string run_bad_graph(const std::string& file_name, const std::string& text,
                            const std::vector<std::string>& needles) {
    const fs::path spec = dir / file_name;
    write_text(spec, text);
    const RunResult r = run_neopipe({"run", mkv.string(), "--graph", spec.string(), "--out", (dir / "t.csv").string()});
    auto all = needles;
    all.push_back(spec.string());
    return expect_one_error(r, all, 1);
  }
};

TEST_F(CliGraph, UnknownKernelIsReportedAtItsLineAndColumn) {
  const std::string line = run_bad_graph("unknown_kernel.yaml", kUnknownKernel, {"unknown kernel", "grey"});
  const auto pos = graph_error_position(line, (dir / "unknown_kernel.yaml").string());
  ASSERT_TRUE(pos) << "expected 'error: PATH:LINE:COL: ...', got: " << line;
  EXPECT_EQ(pos->first, 7);
  EXPECT_EQ(pos->second, 13);
}

TEST_F(CliGraph, YamlSyntaxErrorIsReportedAtItsLine) {
  const std::string line = run_bad_graph("bad_yaml.yaml", kYamlSyntax, {});
  const auto pos = graph_error_position(line, (dir / "bad_yaml.yaml").string());
  ASSERT_TRUE(pos) << "expected 'error: PATH:LINE:COL: ...', got: " << line;
  EXPECT_EQ(pos->first, 7);
  EXPECT_EQ(pos->second, 17) << "the second ':'";
}

TEST_F(CliGraph, CycleWithoutDelayIsReportedAtAnEdgeOfTheCycle) {
  const std::string line = run_bad_graph("cycle.yaml", kCycle, {"cycle"});
  const auto pos = graph_error_position(line, (dir / "cycle.yaml").string());
  ASSERT_TRUE(pos) << "expected 'error: PATH:LINE:COL: ...', got: " << line;
  EXPECT_TRUE(pos->first == 10 || pos->first == 14) << "line " << pos->first << " is not an edge of the cycle";
}

TEST_F(CliGraph, SelfLoopWithoutDelayIsReportedAtItsEdge) {
  const std::string line = run_bad_graph("self_loop.yaml", kSelfLoop, {"cycle"});
  const auto pos = graph_error_position(line, (dir / "self_loop.yaml").string());
  ASSERT_TRUE(pos) << "expected 'error: PATH:LINE:COL: ...', got: " << line;
  EXPECT_EQ(pos->first, 10);
}

// Regression: a node without a `params:` key once failed with "expected a single value" because an
// absent parameter map read as a defined null; omitted parameters must take their defaults.
TEST_F(CliGraph, OmittedParamsTakeTheDocumentedDefaults) {
  const std::string without =
      "name: defaults\n"
      "nodes:\n"
      "  - name: src\n"
      "    kernel: source\n"
      "    params: {format: gray}\n"
      "  - name: blobs\n"
      "    kernel: blobs\n"
      "    inputs: {in: src}\n"
      "outputs: [blobs]\n";
  std::string with_empty = without;
  with_empty.replace(with_empty.find("    inputs: {in: src}"), 0, "    params: {}\n");
  std::string explicit_defaults = without;
  explicit_defaults.replace(explicit_defaults.find("    inputs: {in: src}"), 0,
                            "    params: {threshold: 0, connectivity: 8}\n");
  write_text(dir / "without.yaml", without);
  write_text(dir / "empty.yaml", with_empty);
  write_text(dir / "explicit.yaml", explicit_defaults);
  const std::string reference = run_to_file({png(5), "--graph", (dir / "explicit.yaml").string()}, "explicit.csv");
  EXPECT_EQ(parse_csv(reference).rows.size(), 3u);
  EXPECT_EQ(run_to_file({png(5), "--graph", (dir / "empty.yaml").string()}, "empty.csv"), reference);
  EXPECT_EQ(run_to_file({png(5), "--graph", (dir / "without.yaml").string()}, "without.csv"), reference);
}

TEST_F(CliGraph, GraphWithoutBlobsOutputIsAnError) {
  run_bad_graph("no_blobs.yaml", kNoBlobs, {"no output of type blobs"});
}

// Command-line errors: exit code 2, the flag named.
TEST_F(Cli, BadFlagValuesAreUsageErrors) {
  const std::string csv = (dir / "t.csv").string();
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases{
      {{"run", mkv.string(), "--threads", "0", "--out", csv}, {"--threads"}},
      {{"run", mkv.string(), "--threshold", "300", "--out", csv}, {"--threshold", "300"}},
      {{"run", mkv.string(), "--connectivity", "6", "--out", csv}, {"--connectivity", "6"}},
      {{"run", mkv.string(), "--out", (dir / "x.txt").string()}, {"--out", "x.txt"}},
      {{"run", mkv.string(), "--bogus-flag", "--out", csv}, {"--bogus-flag"}},
      {{"run", mkv.string(), "--graph", (dir / "missing.yaml").string(), "--out", csv}, {"--graph", "missing.yaml"}},
      {{"run", mkv.string(), "--graph", (examples / "blobs.yaml").string(), "--threshold", "100", "--out", csv},
       {"--threshold", "blobs.yaml"}},
      {{"run", mkv.string(), "--graph", (examples / "blobs.yaml").string(), "--connectivity", "4", "--out", csv},
       {"--connectivity"}},
      {{"run", "--out", csv}, {"INPUT"}},
      {{"run", mkv.string(), "--format", "xml", "--out", csv}, {"--format", "xml"}},
      {{"bench", "--size", "64by64", "--json"}, {"--size", "64by64"}},
      {{"bench", "--case", "sparse", "--json"}, {"--case", "sparse"}},
      {{"bench", "--threads", "0", "--json"}, {"--threads"}},
      {{"bench", "--threads", "2", "--scaling", "--json"}, {"--scaling"}},
      {{"bench", "--sweep", "pixels", "--json"}, {"--sweep", "pixels"}},
      {{"bench", "--sweep", "blobs", "--case", "dense", "--json"}, {"--sweep blobs", "dense"}},
      {{"bench", "--sweep", "blobs", "--size", "64x64", "--size", "80x80", "--json"}, {"--sweep blobs", "--size"}},
      {{}, {"subcommand"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(describe(c.args));
    const RunResult r = run_neopipe(c.args);
    expect_one_error(r, c.needles, 2);
  }
  EXPECT_FALSE(fs::exists(dir / "x.txt")) << "--out x.txt must not create the file";
}

// Regression: a mistyped subcommand once got "A subcommand is required", which did not name it.
TEST_F(Cli, UnknownSubcommandIsNamed) {
  const RunResult r = run_neopipe({"frobnicate"});
  expect_one_error(r, {"frobnicate"}, 2);
}

// ---------------------------------------------------------------------------------------------
// 7. Help, kernels, bench

TEST_F(Cli, HelpTextsExitZeroAndMentionTheOptions) {
  const struct {
    std::vector<std::string> args;
    std::vector<std::string> mentions;
  } cases[] = {
      {{"--help"}, {"run", "bench"}},
      {{"run", "--help"},
       {"--graph", "--threshold", "--connectivity", "--out", "--format", "--annotate", "--realtime", "--fps",
        "--threads", "--frames-in-flight", "--moments", "--quiet", "--list-kernels", kHeader}},
      {{"bench", "--help"},
       {"--size", "--threads", "--scaling", "--case", "--sweep", "--video", "--json", "--min-time", "--repeats", "dots",
        "dense", "chain", "floor", "vs opencv", "ns/px", "+MiB", "run/cv decode", "run/decode",
        "peak resident memory"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(describe(c.args));
    const RunResult r = run_neopipe(c.args);
    ASSERT_TRUE(succeeded(r));
    for (const auto& m : c.mentions) EXPECT_TRUE(contains(r.out, m)) << "help lacks " << m << ":\n" << r.out;
  }
}

// The version has one source, project(neopipe VERSION ...) in CMakeLists.txt, which passes it here too.
TEST_F(Cli, VersionIsThePackageVersion) {
  const RunResult r = run_neopipe({"--version"});
  ASSERT_TRUE(succeeded(r));
  EXPECT_EQ(r.out, std::string("neopipe ") + NEOPIPE_EXPECTED_VERSION + "\n");
}

TEST_F(Cli, ListKernelsNamesTheKernelsTheExamplesUse) {
  const RunResult r = run_neopipe({"run", "--list-kernels"});
  ASSERT_TRUE(succeeded(r));
  std::set<std::string> names;
  for (const auto& l : split_lines(r.out)) {
    std::istringstream in(l);
    std::string first;
    if (in >> first) names.insert(first);
  }
  for (const char* k :
       {"source", "gray", "threshold", "blobs", "lut2", "absdiff", "bool3x3", "conv3x3", "convert", "add"}) {
    EXPECT_TRUE(names.count(k)) << "kernel " << k << " not listed:\n" << r.out;
  }
}

// `neopipe bench` with the quickest settings: one short timed run per measurement.
RunResult run_bench(std::vector<std::string> args) {
  args.insert(args.begin(), "bench");
  for (const char* a : {"--min-time", "0.01", "--repeats", "1"}) args.emplace_back(a);
  return run_neopipe(args);
}

/// Parses `bench --json` output; checks the object's metadata and returns its records.
json bench_records(const RunResult& r) {
  json j;
  EXPECT_NO_THROW(j = json::parse(r.out)) << r.out;
  EXPECT_TRUE(j.is_object()) << r.out;
  if (!j.is_object()) return json::array();
  for (const char* k : {"opencv_version", "hardware_threads", "repeats", "min_time_s", "peak_rss_mib", "notes"}) {
    EXPECT_TRUE(j.contains(k)) << k << " missing";
  }
  EXPECT_EQ(j.value("repeats", 0), 1);
  EXPECT_TRUE(j["notes"].is_array());
  // Peak memory is a number on Linux, and no process of this kind fits in 1 MiB.
  EXPECT_TRUE(j["peak_rss_mib"].is_number()) << j["peak_rss_mib"].dump();
  if (j["peak_rss_mib"].is_number()) {
    EXPECT_GT(j["peak_rss_mib"].get<double>(), 1.0);
  }
  EXPECT_TRUE(j["records"].is_array());
  return j.value("records", json::array());
}

// The records of one implementation, in output order.
std::vector<json> of_impl(const json& records, const std::string& impl) {
  std::vector<json> out;
  for (const auto& rec : records) {
    if (rec["impl"] == impl) out.push_back(rec);
  }
  return out;
}

TEST_F(Cli, BenchJsonRecords) {
  const RunResult r = run_bench({"--size", "64x64", "--threads", "1", "--case", "dots", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json records = bench_records(r);
  std::set<std::string> impls;
  for (const auto& rec : records) {
    for (const char* k : {"case", "impl", "graph", "sweep", "width", "height", "blobs", "threads", "fps", "mpix_s",
                          "ns_per_pixel", "rss_growth_mib"}) {
      ASSERT_TRUE(rec.contains(k)) << k << " missing in " << rec.dump();
    }
    EXPECT_EQ(rec.size(), 12u) << rec.dump();
    EXPECT_EQ(rec["case"], "dots");
    EXPECT_TRUE(rec["sweep"].is_null());
    EXPECT_EQ(rec["width"], 64);
    EXPECT_EQ(rec["height"], 64);
    EXPECT_GT(rec["blobs"].get<int>(), 0);
    EXPECT_EQ(rec["threads"], 1);
    const double fps = rec["fps"].get<double>();
    EXPECT_GT(fps, 0);
    EXPECT_NEAR(rec["mpix_s"].get<double>(), fps * 64 * 64 / 1e6, 1e-9 * fps);
    EXPECT_NEAR(rec["ns_per_pixel"].get<double>() * fps * 64 * 64, 1e9, 1e-3);
    EXPECT_TRUE(rec["rss_growth_mib"].is_null() || rec["rss_growth_mib"].get<double>() >= 0) << rec.dump();
    impls.insert(rec["impl"].get<std::string>());
  }
  EXPECT_EQ(impls, (std::set<std::string>{"neopipe", "opencv", "floor"}));
  EXPECT_EQ(records.size(), 3u);
}

TEST_F(Cli, BenchChainCaseRunsAndReports) {
  const RunResult t = run_bench({"--case", "chain", "--size", "96x72", "--threads", "1"});
  ASSERT_TRUE(succeeded(t));
  bool header = false;
  int rows = 0;
  for (const auto& l : split_lines(t.out)) {
    if (contains(l, "neopipe f/s") && contains(l, "vs opencv") && contains(l, "np ns/px")) header = true;
    if (l.rfind("chain ", 0) == 0 && contains(l, "96x72")) ++rows;
  }
  EXPECT_TRUE(header) << t.out;
  EXPECT_EQ(rows, 1) << t.out;
  EXPECT_TRUE(contains(t.out, "peak resident memory")) << t.out;

  const RunResult j = run_bench({"--case", "chain", "--size", "96x72", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(j));
  const json records = bench_records(j);
  // neopipe, opencv, floor, and the Halide composite when this build has Halide (bench_tests test it).
  std::set<std::string> impls;
  for (const auto& rec : records) impls.insert(rec["impl"].get<std::string>());
  impls.erase("halide");
  EXPECT_EQ(impls, (std::set<std::string>{"neopipe", "opencv", "floor"})) << j.out;
  ASSERT_EQ(records.size(), of_impl(records, "halide").empty() ? 3u : 4u) << j.out;
  for (const auto& rec : records) {
    EXPECT_EQ(rec["case"], "chain");
    EXPECT_GT(rec["fps"].get<double>(), 0);
    // The disks survive the opening: neopipe and OpenCV agreed on a non-zero count.
    EXPECT_GT(rec["blobs"].get<int>(), 0);
  }
}

// --graph times a user's graph on the dots frames: examples/blobs.yaml (BGR -> gray -> Otsu -> blobs)
// finds the dots case's disks, and the records say which graph; no OpenCV or Halide records.
TEST_F(Cli, BenchGraphTimesAUserGraphAgainstTheFloor) {
  const std::string graph = (examples / "blobs.yaml").string();
  const RunResult r = run_bench({"--graph", graph, "--case", "dots", "--size", "96x72", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(r)) << r.err;
  const json records = bench_records(r);
  std::set<std::string> graph_impls;
  int dots_blobs = -1;
  int graph_blobs = -2;
  for (const auto& rec : records) {
    if (rec["case"] == "dots") {
      dots_blobs = rec["blobs"].get<int>();
      EXPECT_TRUE(rec["graph"].is_null());
    } else {
      ASSERT_EQ(rec["case"], "graph") << r.out;
      EXPECT_EQ(rec["graph"], graph);
      graph_impls.insert(rec["impl"].get<std::string>());
      graph_blobs = rec["blobs"].get<int>();
      EXPECT_GT(rec["fps"].get<double>(), 0);
    }
  }
  EXPECT_EQ(graph_impls, (std::set<std::string>{"neopipe", "floor"})) << r.out;
  EXPECT_GT(dots_blobs, 0);
  EXPECT_EQ(graph_blobs, dots_blobs) << r.out;

  // A graph without a blob output has no blob count; the table shows '-' for what it lacks.
  const fs::path image_only = dir / "threshold_only.yaml";
  std::ofstream(image_only) << "name: t\nnodes:\n  - name: src\n    kernel: source\n    params: {format: gray}\n"
                               "  - name: t\n    kernel: threshold\n    params: {value: 100}\n    inputs: {in: src}\n"
                               "outputs: [t]\n";
  const RunResult j = run_bench({"--graph", image_only.string(), "--size", "64x64", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(j)) << j.err;
  for (const auto& rec : bench_records(j)) {
    EXPECT_EQ(rec["case"], "graph");
    EXPECT_TRUE(rec["blobs"].is_null());
  }
  const RunResult t = run_bench({"--graph", image_only.string(), "--size", "64x64", "--threads", "1"});
  ASSERT_TRUE(succeeded(t)) << t.err;
  EXPECT_TRUE(contains(t.out, "note: case graph = " + image_only.string())) << t.out;
}

TEST_F(Cli, BenchGraphBadInputIsOneLine) {
  const fs::path bad = dir / "unknown_kernel.yaml";
  std::ofstream(bad) << "name: x\nnodes:\n  - name: src\n    kernel: source\n    params: {format: gray}\n"
                        "  - name: t\n    kernel: nosuch\n    inputs: {in: src}\noutputs: [t]\n";
  for (const auto& [path, needle] : {std::pair{bad.string(), std::string("unknown kernel 'nosuch'")},
                                     std::pair{(dir / "missing.yaml").string(), std::string("cannot open")}}) {
    const RunResult r = run_bench({"--graph", path, "--size", "64x64", "--threads", "1"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(split_lines(r.err).size(), 1u) << r.err;
    EXPECT_TRUE(contains(r.err, path) && contains(r.err, needle)) << r.err;
  }
  const RunResult s = run_bench({"--graph", bad.string(), "--sweep", "blobs"});
  EXPECT_EQ(s.exit_code, 2) << s.err;
}

TEST_F(Cli, BenchSweepSizeGivesOneRowPerSize) {
  const RunResult r = run_bench({"--sweep", "size", "--size", "64x64", "96x72", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json records = bench_records(r);
  std::vector<std::pair<int, int>> sizes;
  for (const auto& rec : of_impl(records, "neopipe")) {
    EXPECT_EQ(rec["sweep"], "size");
    EXPECT_EQ(rec["case"], "dots");
    EXPECT_GT(rec["ns_per_pixel"].get<double>(), 0);
    sizes.emplace_back(rec["width"].get<int>(), rec["height"].get<int>());
  }
  EXPECT_EQ(sizes, (std::vector<std::pair<int, int>>{{64, 64}, {96, 72}}));
  EXPECT_EQ(of_impl(records, "opencv").size(), 2u);
}

TEST_F(Cli, BenchSweepBlobsGrowsTheCountUntilTheFrameIsFull) {
  const RunResult r = run_bench({"--sweep", "blobs", "--size", "160x120", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json j = json::parse(r.out);
  const json records = bench_records(r);
  std::vector<int> counts;
  for (const auto& rec : of_impl(records, "neopipe")) {
    EXPECT_EQ(rec["sweep"], "blobs");
    EXPECT_EQ(rec["width"], 160);
    EXPECT_EQ(rec["height"], 120);
    counts.push_back(rec["blobs"].get<int>());
  }
  ASSERT_GE(counts.size(), 2u) << r.out;
  EXPECT_EQ(counts[0], 10);
  EXPECT_EQ(counts[1], 30);
  EXPECT_TRUE(std::is_sorted(counts.begin(), counts.end())) << r.out;
  // 10000 disks of radius 3 do not fit in 160x120: the sweep says where it stopped.
  EXPECT_LT(counts.size(), 7u);
  ASSERT_EQ(j["notes"].size(), 1u) << r.out;
  EXPECT_TRUE(contains(j["notes"][0].get<std::string>(), "do not fit")) << j["notes"].dump();

  const RunResult t = run_bench({"--sweep", "blobs", "--size", "160x120", "--threads", "1"});
  ASSERT_TRUE(succeeded(t));
  EXPECT_TRUE(contains(t.out, "sweep: blob count")) << t.out;
  EXPECT_TRUE(contains(t.out, "note: ")) << t.out;
}

TEST_F(Cli, BenchThreadListMeasuresEachCountAndShowsScaling) {
  const RunResult r = run_bench({"--case", "dots", "--size", "64x64", "--threads", "1,2", "--json"});
  ASSERT_TRUE(succeeded(r));
  std::vector<int> threads;
  for (const auto& rec : of_impl(bench_records(r), "neopipe")) threads.push_back(rec["threads"].get<int>());
  EXPECT_EQ(threads, (std::vector<int>{1, 2}));

  const RunResult t = run_bench({"--case", "dots", "--size", "64x64", "--threads", "1", "2"});
  ASSERT_TRUE(succeeded(t));
  EXPECT_TRUE(contains(t.out, "thread scaling")) << t.out;
}

TEST_F(Cli, BenchScalingRunsOneToAllHardwareThreads) {
  const RunResult r = run_bench({"--case", "dots", "--size", "64x64", "--scaling", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json j = json::parse(r.out);
  std::vector<int> threads;
  for (const auto& rec : of_impl(bench_records(r), "neopipe")) threads.push_back(rec["threads"].get<int>());
  ASSERT_FALSE(threads.empty());
  EXPECT_EQ(threads.front(), 1);
  EXPECT_EQ(threads.back(), j["hardware_threads"].get<int>());
  EXPECT_TRUE(std::is_sorted(threads.begin(), threads.end()));
}

TEST_F(Cli, BenchVideoReportsDecodeOnlyAndRunRates) {
  const RunResult r = run_bench({"--video", avi.string(), "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json records = bench_records(r);
  // --video alone measures only the video: cv::VideoCapture, neopipe's reader, and the run without and
  // with its CSV table.
  ASSERT_EQ(records.size(), 4u) << r.out;
  std::set<std::string> impls;
  for (const auto& rec : records) {
    EXPECT_EQ(rec["case"], "video");
    EXPECT_EQ(rec["file"], avi.string());
    EXPECT_EQ(rec["width"], kW);
    EXPECT_EQ(rec["height"], kH);
    EXPECT_EQ(rec["frames"], kFrames);
    EXPECT_EQ(rec["threads"], 1);
    EXPECT_GT(rec["fps"].get<double>(), 0);
    impls.insert(rec["impl"].get<std::string>());
  }
  EXPECT_EQ(impls, (std::set<std::string>{"opencv_decode", "decode", "run", "run_csv"}));

  const RunResult t = run_bench({"--video", avi.string(), "--threads", "1"});
  ASSERT_TRUE(succeeded(t));
  EXPECT_TRUE(contains(t.out, "cv decode f/s") && contains(t.out, " decode f/s") && contains(t.out, "run f/s") &&
              contains(t.out, "run/cv decode") && contains(t.out, "run/decode") && contains(t.out, "run+csv f/s") &&
              contains(t.out, "run+csv/cv decode"))
      << t.out;
  EXPECT_FALSE(contains(t.out, "vs opencv")) << "no synthetic cases without --case:\n" << t.out;
}

// A timed run shorter than the video measures its first frames only; the bench says so, with the
// --min-time that makes each run a whole pass, and says nothing when every run was one.
TEST_F(Cli, BenchVideoNotesTimedRunsShorterThanTheVideo) {
  const RunResult whole =
      run_neopipe({"bench", "--video", avi.string(), "--threads", "1", "--repeats", "1", "--min-time", "2", "--json"});
  // The note appears when a timed run's --min-time ends before the video does: 2 s cover the short
  // clip unless it decodes below a few frames/s (0.5 s did not, under a sanitizer with the suite
  // running beside).
  ASSERT_TRUE(succeeded(whole));
  EXPECT_TRUE(json::parse(whole.out)["notes"].empty()) << whole.out;

  const std::string vtest = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";  // 795 frames
  if (!fs::exists(vtest)) GTEST_SKIP() << vtest << " not installed";
  const RunResult part = run_bench({"--video", vtest, "--threads", "1", "--json"});  // 0.01 s runs
  ASSERT_TRUE(succeeded(part));
  const json notes = json::parse(part.out)["notes"];
  ASSERT_EQ(notes.size(), 1U) << part.out;
  const std::string note = notes[0].get<std::string>();
  EXPECT_TRUE(contains(note, "795 frames") && contains(note, "--min-time")) << note;
  const RunResult text = run_bench({"--video", vtest, "--threads", "1"});
  ASSERT_TRUE(succeeded(text));
  EXPECT_TRUE(contains(text.out, "note: the timed runs covered about the first")) << text.out;
}

TEST_F(Cli, BenchVideoWithACaseMeasuresBoth) {
  const RunResult r =
      run_bench({"--video", avi.string(), "--case", "dots", "--size", "64x64", "--threads", "1", "--json"});
  ASSERT_TRUE(succeeded(r));
  const json records = bench_records(r);
  std::set<std::string> cases;
  for (const auto& rec : records) cases.insert(rec["case"].get<std::string>());
  EXPECT_EQ(cases, (std::set<std::string>{"dots", "video"}));
}

TEST_F(Cli, BenchVideoBadFilesAreOneLineErrors) {
  const std::string missing = (dir / "missing.avi").string();
  expect_one_error(run_bench({"--video", missing}), {missing, "no such file"}, 1);
  const fs::path text = dir / "fake.mp4";
  write_text(text, "this is plain text, not an MP4 video\n");
  expect_one_error(run_bench({"--video", text.string(), "--json"}), {text.string(), "neither an image nor a video"}, 1);
  expect_one_error(run_bench({"--video", png(0)}), {png(0), "not a video"}, 1);
  expect_one_error(run_bench({"--video", png_dir.string()}), {png_dir.string(), "not a video"}, 1);
}

}  // namespace
