// Tests of what a run produces. io::BlobTableWriter: the CSV header is exactly
// "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy" (+ ",mu20,mu11,mu02" with moments), rows come in
// write order, every double reads back bit-identical with std::strtod, JSON Lines rows parse with
// nlohmann::json and carry the same fields, table_format_for maps extensions, and an uncreatable
// path throws. RunStats: nearest-rank latency quantiles and the one-line summary. run_stream: batch
// mode over an image sequence processes every frame in order with the right counts and the same
// blobs as the executor alone, stops on request, and reports reading and sink errors after the
// earlier frames; real-time mode at 1000 frames/s with a test node that holds its first frame until
// the source has moved on (so drops are certain, without timing) keeps
// frames_read == frames_processed + frames_dropped.

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/io/blob_table_writer.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline/run_stats.hpp"
#include "pipeline/stream_runner.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)
namespace io = neopipe::pipeline::io;
namespace fs = std::filesystem;

namespace {

io::TableOptions table_options(io::TableFormat format, bool moments) {
  io::TableOptions o;
  o.format = format;
  o.moments = moments;
  return o;
}

neopipe::kernels::Blob make_blob(std::int64_t area, int x0, int y0, int w, int h, double cx, double cy, double wcx,
                                 double wcy, double mu20, double mu11, double mu02) {
  neopipe::kernels::Blob b;
  b.area = area;
  b.x0 = x0;
  b.y0 = y0;
  b.width = w;
  b.height = h;
  b.cx = cx;
  b.cy = cy;
  b.wcx = wcx;
  b.wcy = wcy;
  b.mu20 = mu20;
  b.mu11 = mu11;
  b.mu02 = mu02;
  return b;
}

// Blobs whose real numbers are hard to print exactly: thirds, tenths, tiny and huge magnitudes,
// integers, negatives.
pl::BlobList tricky_blobs() {
  return {
      make_blob(3, 0, 0, 2, 2, 1.0 / 3, 2.0 / 3, 0.1, 0.2 + 0.1, 2.0 / 9, -1.0 / 9, 2.0 / 9),
      make_blob(123456789012LL, 1000, 2000, 640, 480, 319.5, 239.5, 1e-7, 123456.78901234567, 1.7976931348623157e308,
                -0.0, 4.9406564584124654e-324),
      make_blob(1, 7, 9, 1, 1, 7, 9, 7, 9, 0, 0, 0),
  };
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

// Parses a whole CSV field as a double; fails the test if anything is left over.
double parse_double(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << "'" << text << "' is not a plain number";
  return v;
}

// Bit-identical, so -0.0 and 0.0 differ and the test shows a lost sign.
void expect_same_double(double got, double want, const std::string& what) {
  EXPECT_EQ(std::signbit(got), std::signbit(want)) << what;
  EXPECT_EQ(got, want) << what << ": got " << got << ", want " << want;
}

// Checks one CSV row against (frame, index, blob).
void expect_csv_row(const std::string& line, std::int64_t frame, size_t index, const neopipe::kernels::Blob& b,
                    bool moments) {
  SCOPED_TRACE(line);
  const auto f = split_csv(line);
  ASSERT_EQ(f.size(), moments ? 14U : 11U);
  EXPECT_EQ(std::stoll(f[0]), frame);
  EXPECT_EQ(std::stoull(f[1]), index);
  EXPECT_EQ(std::stoll(f[2]), b.area);
  expect_same_double(parse_double(f[3]), b.cx, "cx");
  expect_same_double(parse_double(f[4]), b.cy, "cy");
  EXPECT_EQ(std::stoi(f[5]), b.x0);
  EXPECT_EQ(std::stoi(f[6]), b.y0);
  EXPECT_EQ(std::stoi(f[7]), b.width);
  EXPECT_EQ(std::stoi(f[8]), b.height);
  expect_same_double(parse_double(f[9]), b.wcx, "wcx");
  expect_same_double(parse_double(f[10]), b.wcy, "wcy");
  if (moments) {
    expect_same_double(parse_double(f[11]), b.mu20, "mu20");
    expect_same_double(parse_double(f[12]), b.mu11, "mu11");
    expect_same_double(parse_double(f[13]), b.mu02, "mu02");
  }
}

std::string write_table(const io::TableOptions& options,
                        const std::vector<std::pair<std::int64_t, pl::BlobList>>& frames,
                        std::int64_t* rows = nullptr) {
  std::ostringstream out;
  io::BlobTableWriter w(out, options);
  for (const auto& [frame, blobs] : frames) w.write(frame, blobs);
  if (rows != nullptr) *rows = w.rows();
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Stream-runner helpers

std::vector<cv::Mat> disc_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, CV_8UC3);
    rng.fill(f, cv::RNG::UNIFORM, 10, 70);
    for (int d = 0; d < 6; ++d) {
      cv::circle(f, {rng.uniform(0, size.width), rng.uniform(0, size.height)}, rng.uniform(2, 9),
                 cv::Scalar::all(rng.uniform(150, 256)), cv::FILLED);
    }
    frames.push_back(f);
  }
  return frames;
}

// Writes frames into `dir` as f000.png, f001.png, ...
void write_sequence(const TempDir& dir, const std::vector<cv::Mat>& frames) {
  for (size_t i = 0; i < frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "f%03zu.png", i);
    ASSERT_TRUE(cv::imwrite(dir.file(name), frames[i]));
  }
}

// How far the source has been read, shared with a test node that waits for it.
struct ReadProgress {
  std::mutex m;
  std::condition_variable cv;
  int taken = 0;  // frames taken from the source
  bool ended = false;

  void advance(bool got_one) {
    std::lock_guard lk(m);
    if (got_one) {
      ++taken;
    } else {
      ended = true;
    }
    cv.notify_all();
  }
  void wait_until_taken(int n) {
    std::unique_lock lk(m);
    cv.wait(lk, [&] { return taken >= n || ended; });
  }
};

// A source that reports every frame taken from the source it wraps.
class CountingSource final : public io::FrameSource {
 public:
  CountingSource(std::unique_ptr<io::FrameSource> inner, std::shared_ptr<ReadProgress> progress)
      : inner_(std::move(inner)), progress_(std::move(progress)) {}
  std::optional<io::SourceFrame> next() override {
    auto f = inner_->next();
    progress_->advance(f.has_value());
    return f;
  }
  std::string description() const override { return inner_->description(); }
  double fps() const override { return inner_->fps(); }
  std::optional<std::int64_t> frame_count() const override { return inner_->frame_count(); }

 private:
  std::unique_ptr<io::FrameSource> inner_;
  std::shared_ptr<ReadProgress> progress_;
};

// Copies its gray input, but holds the first frame it gets until the source has given out
// `hold_until` frames: a stage that is slow exactly when the test needs it to be.
class HoldFirstFrameNode final : public pl::Node {
 public:
  HoldFirstFrameNode(std::shared_ptr<ReadProgress> progress, int hold_until)
      : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, neopipe::kernels::Footprint::frame),
        progress_(std::move(progress)),
        hold_until_(hold_until) {}
  void begin_frame(pl::NodeIO& io) override {
    if (first_) {
      first_ = false;
      progress_->wait_until_taken(hold_until_);
    }
    io.image(0).copyTo(io.out_image(0));
  }

 private:
  std::shared_ptr<ReadProgress> progress_;
  int hold_until_;
  bool first_ = true;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// BlobTableWriter

TEST(BlobTableWriter, CsvHeaderExactly) {
  EXPECT_EQ(write_table(table_options(io::TableFormat::csv, false), {}), "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy\n");
  EXPECT_EQ(write_table(table_options(io::TableFormat::csv, true), {}),
            "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy,mu20,mu11,mu02\n");
  EXPECT_EQ(write_table(table_options(io::TableFormat::jsonl, true), {}), "");  // JSON Lines has no header
}

TEST(BlobTableWriter, CsvRowsInOrderAndExact) {
  const pl::BlobList blobs = tricky_blobs();
  for (const bool moments : {false, true}) {
    SCOPED_TRACE(moments ? "with moments" : "without moments");
    std::int64_t rows = 0;
    const std::string text = write_table(table_options(io::TableFormat::csv, moments),
                                         {{3, {blobs[0], blobs[1]}}, {4, {}}, {7, {blobs[2]}}, {8, {blobs[1]}}}, &rows);
    EXPECT_EQ(rows, 4);
    const auto lines = lines_of(text);
    ASSERT_EQ(lines.size(), 5U);
    EXPECT_EQ(lines[0], std::string("frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy") + (moments ? ",mu20,mu11,mu02" : ""));
    expect_csv_row(lines[1], 3, 0, blobs[0], moments);
    expect_csv_row(lines[2], 3, 1, blobs[1], moments);
    expect_csv_row(lines[3], 7, 0, blobs[2], moments);
    expect_csv_row(lines[4], 8, 0, blobs[1], moments);
    EXPECT_EQ(text.back(), '\n');
  }
  // A simple row, character for character: integers without decimals, shortest round-trip reals.
  const auto lines = lines_of(write_table(table_options(io::TableFormat::csv, false), {{12, {blobs[2]}}}));
  ASSERT_EQ(lines.size(), 2U);
  EXPECT_EQ(lines[1], "12,0,1,7,9,7,9,1,1,7,9");
}

TEST(BlobTableWriter, JsonLinesCarryTheSameFields) {
  const pl::BlobList blobs = tricky_blobs();
  for (const bool moments : {false, true}) {
    SCOPED_TRACE(moments ? "with moments" : "without moments");
    std::int64_t rows = 0;
    const std::string text = write_table(table_options(io::TableFormat::jsonl, moments),
                                         {{5, {blobs[0], blobs[1]}}, {6, {}}, {9, {blobs[2]}}}, &rows);
    EXPECT_EQ(rows, 3);
    const auto lines = lines_of(text);
    ASSERT_EQ(lines.size(), 3U);
    const std::int64_t frames[] = {5, 5, 9};
    const size_t indices[] = {0, 1, 0};
    const neopipe::kernels::Blob* expected[] = {&blobs[0], &blobs[1], &blobs[2]};
    for (size_t i = 0; i < 3; ++i) {
      SCOPED_TRACE(lines[i]);
      const nlohmann::json j = nlohmann::json::parse(lines[i]);
      ASSERT_TRUE(j.is_object());
      EXPECT_EQ(j.size(), moments ? 14U : 11U);
      const auto& b = *expected[i];
      EXPECT_EQ(j.at("frame").get<std::int64_t>(), frames[i]);
      EXPECT_EQ(j.at("blob").get<std::size_t>(), indices[i]);
      EXPECT_EQ(j.at("area").get<std::int64_t>(), b.area);
      EXPECT_EQ(j.at("x0").get<int>(), b.x0);
      EXPECT_EQ(j.at("y0").get<int>(), b.y0);
      EXPECT_EQ(j.at("w").get<int>(), b.width);
      EXPECT_EQ(j.at("h").get<int>(), b.height);
      // Compared by value: JSON readers may take "-0" for the integer 0.
      EXPECT_EQ(j.at("cx").get<double>(), b.cx);
      EXPECT_EQ(j.at("cy").get<double>(), b.cy);
      EXPECT_EQ(j.at("wcx").get<double>(), b.wcx);
      EXPECT_EQ(j.at("wcy").get<double>(), b.wcy);
      if (moments) {
        EXPECT_EQ(j.at("mu20").get<double>(), b.mu20);
        EXPECT_EQ(j.at("mu11").get<double>(), b.mu11);
        EXPECT_EQ(j.at("mu02").get<double>(), b.mu02);
      } else {
        EXPECT_FALSE(j.contains("mu20"));
      }
    }
  }
}

// The exact text of a table with values whose printing is easy to get wrong: thirds and tenths,
// negatives, -0, integers held as doubles, 1e-7, denormals, the largest double, 1e15 (fixed) and
// 1e16 (exponent), 2^53 + 1, extreme integers, calibrated X,Y. The expected text is what the writer
// printed before its formatting was made cheaper (runtime fmt format strings), so a faster
// formatter must keep every byte.
TEST(BlobTableWriter, TextIsByteForByteTheSameForAwkwardValues) {
  pl::BlobList blobs = tricky_blobs();
  blobs.push_back(make_blob(9223372036854775807LL, -5, -2147483647 - 1, 2147483647, 0, -12.75, -1e-7, 1e15, 1e16,
                            1.2345678901234568e17, 1e21, -1e22));
  blobs.push_back(make_blob(42, 3, 4, 5, 6, 0.0001, 0.00001, 123456789.0, 100.0, -3.0, 2.5e-308, 9007199254740993.0));
  const auto to_world = [](const std::vector<cv::Point2d>& c) {
    std::vector<cv::Point2d> w;
    for (const auto& p : c) w.emplace_back(p.x * -2.5, p.y * 1e-3);
    return w;
  };
  const auto table = [&](io::TableFormat format, bool extra) {
    io::TableOptions o = table_options(format, extra);
    if (extra) o.to_world = to_world;
    return write_table(o, {{0, blobs}, {1234567890123LL, {blobs[2]}}});
  };
  EXPECT_EQ(table(io::TableFormat::csv, false),
            "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy\n"
            "0,0,3,0.3333333333333333,0.6666666666666666,0,0,2,2,0.1,0.30000000000000004\n"
            "0,1,123456789012,319.5,239.5,1000,2000,640,480,1e-07,123456.78901234567\n"
            "0,2,1,7,9,7,9,1,1,7,9\n"
            "0,3,9223372036854775807,-12.75,-1e-07,-5,-2147483648,2147483647,0,1000000000000000,1e+16\n"
            "0,4,42,0.0001,1e-05,3,4,5,6,123456789,100\n"
            "1234567890123,0,1,7,9,7,9,1,1,7,9\n");
  EXPECT_EQ(table(io::TableFormat::csv, true),
            "frame,blob,area,cx,cy,x0,y0,w,h,wcx,wcy,mu20,mu11,mu02,X,Y\n"
            "0,0,3,0.3333333333333333,0.6666666666666666,0,0,2,2,0.1,0.30000000000000004,0.2222222222222222,-0."
            "1111111111111111,0.2222222222222222,-0.25,0.00030000000000000003\n"
            "0,1,123456789012,319.5,239.5,1000,2000,640,480,1e-07,123456.78901234567,1.7976931348623157e+308,-0,5e-324,"
            "-2.5e-07,123.45678901234568\n"
            "0,2,1,7,9,7,9,1,1,7,9,0,0,0,-17.5,0.009000000000000001\n"
            "0,3,9223372036854775807,-12.75,-1e-07,-5,-2147483648,2147483647,0,1000000000000000,1e+16,1."
            "2345678901234568e+17,1e+21,-1e+22,-2500000000000000,10000000000000\n"
            "0,4,42,0.0001,1e-05,3,4,5,6,123456789,100,-3,2.5e-308,9007199254740992,-308641972.5,0.1\n"
            "1234567890123,0,1,7,9,7,9,1,1,7,9,0,0,0,-17.5,0.009000000000000001\n");
  EXPECT_EQ(
      table(io::TableFormat::jsonl, false),
      "{\"frame\":0,\"blob\":0,\"area\":3,\"cx\":0.3333333333333333,\"cy\":0.6666666666666666,\"x0\":0,\"y0\":0,\"w\":"
      "2,\"h\":2,\"wcx\":0.1,\"wcy\":0.30000000000000004}\n"
      "{\"frame\":0,\"blob\":1,\"area\":123456789012,\"cx\":319.5,\"cy\":239.5,\"x0\":1000,\"y0\":2000,\"w\":640,\"h\":"
      "480,\"wcx\":1e-07,\"wcy\":123456.78901234567}\n"
      "{\"frame\":0,\"blob\":2,\"area\":1,\"cx\":7,\"cy\":9,\"x0\":7,\"y0\":9,\"w\":1,\"h\":1,\"wcx\":7,\"wcy\":9}\n"
      "{\"frame\":0,\"blob\":3,\"area\":9223372036854775807,\"cx\":-12.75,\"cy\":-1e-07,\"x0\":-5,\"y0\":-2147483648,"
      "\"w\":2147483647,\"h\":0,\"wcx\":1000000000000000,\"wcy\":1e+16}\n"
      "{\"frame\":0,\"blob\":4,\"area\":42,\"cx\":0.0001,\"cy\":1e-05,\"x0\":3,\"y0\":4,\"w\":5,\"h\":6,\"wcx\":"
      "123456789,\"wcy\":100}\n"
      "{\"frame\":1234567890123,\"blob\":0,\"area\":1,\"cx\":7,\"cy\":9,\"x0\":7,\"y0\":9,\"w\":1,\"h\":1,\"wcx\":7,"
      "\"wcy\":9}\n");
  EXPECT_EQ(
      table(io::TableFormat::jsonl, true),
      "{\"frame\":0,\"blob\":0,\"area\":3,\"cx\":0.3333333333333333,\"cy\":0.6666666666666666,\"x0\":0,\"y0\":0,\"w\":"
      "2,\"h\":2,\"wcx\":0.1,\"wcy\":0.30000000000000004,\"mu20\":0.2222222222222222,\"mu11\":-0.1111111111111111,"
      "\"mu02\":0.2222222222222222,\"X\":-0.25,\"Y\":0.00030000000000000003}\n"
      "{\"frame\":0,\"blob\":1,\"area\":123456789012,\"cx\":319.5,\"cy\":239.5,\"x0\":1000,\"y0\":2000,\"w\":640,\"h\":"
      "480,\"wcx\":1e-07,\"wcy\":123456.78901234567,\"mu20\":1.7976931348623157e+308,\"mu11\":-0,\"mu02\":5e-324,\"X\":"
      "-2.5e-07,\"Y\":123.45678901234568}\n"
      "{\"frame\":0,\"blob\":2,\"area\":1,\"cx\":7,\"cy\":9,\"x0\":7,\"y0\":9,\"w\":1,\"h\":1,\"wcx\":7,\"wcy\":9,"
      "\"mu20\":0,\"mu11\":0,\"mu02\":0,\"X\":-17.5,\"Y\":0.009000000000000001}\n"
      "{\"frame\":0,\"blob\":3,\"area\":9223372036854775807,\"cx\":-12.75,\"cy\":-1e-07,\"x0\":-5,\"y0\":-2147483648,"
      "\"w\":2147483647,\"h\":0,\"wcx\":1000000000000000,\"wcy\":1e+16,\"mu20\":1.2345678901234568e+17,\"mu11\":1e+21,"
      "\"mu02\":-1e+22,\"X\":-2500000000000000,\"Y\":10000000000000}\n"
      "{\"frame\":0,\"blob\":4,\"area\":42,\"cx\":0.0001,\"cy\":1e-05,\"x0\":3,\"y0\":4,\"w\":5,\"h\":6,\"wcx\":"
      "123456789,\"wcy\":100,\"mu20\":-3,\"mu11\":2.5e-308,\"mu02\":9007199254740992,\"X\":-308641972.5,\"Y\":0.1}\n"
      "{\"frame\":1234567890123,\"blob\":0,\"area\":1,\"cx\":7,\"cy\":9,\"x0\":7,\"y0\":9,\"w\":1,\"h\":1,\"wcx\":7,"
      "\"wcy\":9,\"mu20\":0,\"mu11\":0,\"mu02\":0,\"X\":-17.5,\"Y\":0.009000000000000001}\n");
}

TEST(BlobTableWriter, WritesFilesAndRefusesUncreatablePaths) {
  const TempDir dir("neopipe_blob_table");
  const pl::BlobList blobs = tricky_blobs();
  const std::string path = dir.file("blobs.csv");
  std::ofstream(path) << "old content that must go\n";
  {
    io::BlobTableWriter w(path, table_options(io::TableFormat::csv, true));
    w.write(0, blobs);
    // Each write is flushed: the rows are in the file before the writer goes away.
    std::ifstream in(path);
    std::stringstream now;
    now << in.rdbuf();
    EXPECT_EQ(now.str(), write_table(table_options(io::TableFormat::csv, true), {{0, blobs}}));
  }
  std::ifstream in(path);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), write_table(table_options(io::TableFormat::csv, true), {{0, blobs}}));

  const std::string nowhere = dir.file("no/such/dir/blobs.csv");
  try {
    io::BlobTableWriter w(nowhere, {});
    ADD_FAILURE() << "a writer was made for " << nowhere;
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(nowhere + ": cannot create", 0), 0U) << e.what();
  }
  EXPECT_THROW(io::BlobTableWriter(dir.str(), {}), std::runtime_error);  // a directory
}

// A file that fills up mid-frame (here: the process's file-size limit, which fails write() with
// EFBIG as a full disk fails it with ENOSPC) keeps the rows of whole frames only: the part of the
// frame that got out is cut off again, and the error names the file, the cause and the rows kept.
TEST(BlobTableWriter, AFileThatFillsUpEndsWithTheLastWholeFrame) {
  const TempDir dir("neopipe_blob_table_full");
  const std::string path = dir.file("blobs.csv");
  const pl::BlobList blobs = tricky_blobs();
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // else the limit kills the process
  rlimit limit = old;
  limit.rlim_cur = 2000;  // bytes: the header and a few frames
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  std::string message;
  std::int64_t kept = -1;
  {
    io::BlobTableWriter w(path, table_options(io::TableFormat::csv, true));
    try {
      for (std::int64_t frame = 0; frame < 100; ++frame) w.write(frame, blobs);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    kept = w.rows();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(message.rfind(path + ": write failed: File too large (the table keeps its ", 0), 0U) << message;
  const std::string text = [&] {
    std::ifstream in(path);
    std::stringstream all;
    all << in.rdbuf();
    return all.str();
  }();
  ASSERT_GT(kept, 0);
  const auto frames = kept / static_cast<std::int64_t>(blobs.size());
  EXPECT_EQ(kept % static_cast<std::int64_t>(blobs.size()), 0);
  std::vector<std::pair<std::int64_t, pl::BlobList>> whole;
  for (std::int64_t f = 0; f < frames; ++f) whole.emplace_back(f, blobs);
  EXPECT_EQ(text, write_table(table_options(io::TableFormat::csv, true), whole));
  EXPECT_LE(text.size(), 2000U);
}

TEST(BlobTableWriter, FormatFromTheFileName) {
  EXPECT_EQ(io::table_format_for("out/blobs.csv"), io::TableFormat::csv);
  EXPECT_EQ(io::table_format_for("blobs.jsonl"), io::TableFormat::jsonl);
  EXPECT_EQ(io::table_format_for("/tmp/x.y/blobs.ndjson"), io::TableFormat::jsonl);
  EXPECT_EQ(io::table_format_for("BLOBS.CSV"), io::TableFormat::csv);
  EXPECT_EQ(io::table_format_for("blobs.JsonL"), io::TableFormat::jsonl);
  EXPECT_EQ(io::table_format_for("blobs.json"), std::nullopt);
  EXPECT_EQ(io::table_format_for("blobs.txt"), std::nullopt);
  EXPECT_EQ(io::table_format_for("blobs"), std::nullopt);
  EXPECT_EQ(io::table_format_for("csv"), std::nullopt);
  EXPECT_EQ(io::table_format_for("dir.csv/blobs"), std::nullopt);
}

// ---------------------------------------------------------------------------------------------
// RunStats

TEST(RunStats, LatencyQuantileIsNearestRank) {
  pl::RunStats s;
  EXPECT_EQ(s.latency_quantile(0.5), 0);  // no frames
  for (double v : {0.005, 0.001, 0.004, 0.002, 0.003}) s.latency.add(v);
  EXPECT_EQ(s.latency.count(), 5);
  // The extremes are exact; inner quantiles are bucket centres within 0.14 %.
  EXPECT_EQ(s.latency_quantile(0.0), 0.001);
  EXPECT_EQ(s.latency_quantile(0.2), 0.001);                     // rank ceil(1.0) = 1
  EXPECT_NEAR(s.latency_quantile(0.21), 0.002, 0.002 * 0.0014);  // rank ceil(1.05) = 2
  EXPECT_NEAR(s.latency_quantile(0.5), 0.003, 0.003 * 0.0014);   // rank ceil(2.5) = 3
  EXPECT_NEAR(s.latency_quantile(0.8), 0.004, 0.004 * 0.0014);
  EXPECT_EQ(s.latency_quantile(0.99), 0.005);
  EXPECT_EQ(s.latency_quantile(1.0), 0.005);
  EXPECT_EQ(s.latency_quantile(2.0), 0.005);  // clamped
  EXPECT_EQ(s.latency_quantile(-1.0), 0.001);
}

// A run of any length keeps the same memory, and quantiles stay accurate over wide ranges.
TEST(RunStats, LatencyHistogramIsAccurateOverSixDecades) {
  pl::LatencyHistogram h;
  std::vector<double> values;
  cv::RNG rng(7);
  for (int i = 0; i < 20000; ++i) values.push_back(std::pow(10.0, rng.uniform(-6.0, 0.0)));
  for (double v : values) h.add(v);
  std::sort(values.begin(), values.end());
  for (double q : {0.01, 0.1, 0.5, 0.9, 0.99, 0.999}) {
    const auto rank = static_cast<size_t>(std::ceil(q * static_cast<double>(values.size()))) - 1;
    EXPECT_NEAR(h.quantile(q), values[rank], values[rank] * 0.0014) << "q " << q;
  }
  EXPECT_EQ(h.min(), values.front());
  EXPECT_EQ(h.max(), values.back());
  h.add(-1);  // clock oddities count as 0
  EXPECT_EQ(h.min(), 0);
}

TEST(RunStats, Summary) {
  pl::RunStats s;
  s.frames_read = 123;
  s.frames_processed = 120;
  s.frames_dropped = 3;
  s.blobs = 1440;
  s.seconds = 0.41;
  for (double v : {0.002, 0.001, 0.010}) s.latency.add(v);
  EXPECT_DOUBLE_EQ(s.frames_per_second(), 120 / 0.41);
  EXPECT_EQ(s.summary(),
            "120 frames, 3 dropped, 1440 blobs in 0.410 s (292.7 frames/s); latency p50 2.00 ms, p99 10.00 ms");
  s.interrupted = true;
  EXPECT_EQ(s.summary(),
            "120 frames, 3 dropped, 1440 blobs in 0.410 s (292.7 frames/s); latency p50 2.00 ms, p99 10.00 ms "
            "(interrupted)");
  s.realtime = true;  // real-time runs also report how far reading fell behind
  s.max_reader_lag_s = 0.01234;
  EXPECT_EQ(s.summary(),
            "120 frames, 3 dropped, 1440 blobs in 0.410 s (292.7 frames/s); latency p50 2.00 ms, p99 10.00 ms; "
            "reader lag max 12.3 ms (interrupted)");
  const pl::RunStats empty;
  EXPECT_EQ(empty.frames_per_second(), 0);
  EXPECT_EQ(empty.summary(),
            "0 frames, 0 dropped, 0 blobs in 0.000 s (0.0 frames/s); latency p50 0.00 ms, p99 0.00 ms");
}

// ---------------------------------------------------------------------------------------------
// run_stream

TEST(RunStream, BatchModeProcessesEveryFrameInOrder) {
  const TempDir dir("neopipe_run_stream_batch");
  const auto frames = disc_frames(14, {64, 48}, 31);
  write_sequence(dir, frames);
  const auto expected = pl::run_frames(pl::compile(pl::blob_graph(), pl::standard_kernels()), frames, {.threads = 1});

  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  pl::RunStats stats;
  std::vector<std::int64_t> indices;
  std::vector<pl::BlobList> tables;
  std::vector<std::int64_t> progress;
  pl::StreamOptions options;
  options.executor = {.threads = 4, .frames_in_flight = 3};
  options.progress = [&](const pl::RunStats& s) { progress.push_back(s.frames_processed); };
  pl::run_stream(
      *source, pl::compile(pl::blob_graph(), pl::standard_kernels()), options,
      [&](const pl::FrameResult& r) {
        indices.push_back(r.index);
        tables.push_back(std::get<pl::BlobList>(r.outputs.at(0)));
      },
      stats);

  EXPECT_EQ(stats.frames_read, 14);
  EXPECT_EQ(stats.frames_processed, 14);
  EXPECT_EQ(stats.frames_dropped, 0);
  EXPECT_FALSE(stats.interrupted);
  EXPECT_EQ(stats.latency.count(), 14);
  EXPECT_GT(stats.seconds, 0);
  std::int64_t blobs = 0;
  ASSERT_EQ(tables.size(), 14U);
  for (size_t i = 0; i < tables.size(); ++i) {
    EXPECT_EQ(indices[i], static_cast<std::int64_t>(i));
    blobs += static_cast<std::int64_t>(tables[i].size());
    const auto& want = std::get<pl::BlobList>(expected[i].outputs[0]);
    ASSERT_EQ(tables[i].size(), want.size()) << "frame " << i;
    for (size_t k = 0; k < want.size(); ++k) {
      EXPECT_EQ(tables[i][k].area, want[k].area);
      EXPECT_EQ(tables[i][k].wcx, want[k].wcx);
      EXPECT_EQ(tables[i][k].wcy, want[k].wcy);
    }
  }
  EXPECT_EQ(stats.blobs, blobs);
  EXPECT_GT(blobs, 14);
  EXPECT_EQ(progress, (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14}));
}

TEST(RunStream, StopRequestEndsReadingButFinishesFramesInFlight) {
  const TempDir dir("neopipe_run_stream_stop");
  write_sequence(dir, disc_frames(12, {32, 24}, 32));
  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  std::atomic<bool> stop{false};
  pl::StreamOptions options;
  options.executor = {.threads = 1, .frames_in_flight = 2};
  options.stop = &stop;
  options.progress = [&](const pl::RunStats& s) {
    if (s.frames_processed == 3) stop = true;
  };
  pl::RunStats stats;
  std::int64_t delivered = 0;
  pl::run_stream(
      *source, pl::compile(pl::blob_graph(), pl::standard_kernels()), options,
      [&](const pl::FrameResult&) { ++delivered; }, stats);
  EXPECT_TRUE(stats.interrupted);
  EXPECT_GE(stats.frames_read, 3);
  EXPECT_LT(stats.frames_read, 12);  // at most a pipeline's worth read after the request
  EXPECT_EQ(stats.frames_processed, stats.frames_read);
  EXPECT_EQ(delivered, stats.frames_processed);

  // Stopped before it starts: nothing is read.
  auto again = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  std::atomic<bool> stopped{true};
  pl::StreamOptions at_once;
  at_once.stop = &stopped;
  pl::RunStats none;
  pl::run_stream(
      *again, pl::compile(pl::blob_graph(), pl::standard_kernels()), at_once, [](const pl::FrameResult&) {}, none);
  EXPECT_TRUE(none.interrupted);
  EXPECT_EQ(none.frames_read, 0);
  EXPECT_EQ(none.frames_processed, 0);
}

TEST(RunStream, ReadingErrorComesAfterTheEarlierFrames) {
  const TempDir dir("neopipe_run_stream_read_error");
  const auto frames = disc_frames(3, {32, 24}, 33);
  ASSERT_TRUE(cv::imwrite(dir.file("a.png"), frames[0]));
  ASSERT_TRUE(cv::imwrite(dir.file("b.png"), frames[1]));
  std::ofstream(dir.file("c.png")) << "not a png";
  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  pl::RunStats stats;
  std::vector<std::int64_t> delivered;
  try {
    pl::run_stream(
        *source, pl::compile(pl::blob_graph(), pl::standard_kernels()), {},
        [&](const pl::FrameResult& r) { delivered.push_back(r.index); }, stats);
    ADD_FAILURE() << "the corrupt image went unnoticed";
  } catch (const io::SourceError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("c.png")), std::string::npos) << e.what();
  }
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(stats.frames_read, 2);
  EXPECT_EQ(stats.frames_processed, 2);
}

TEST(RunStream, SinkErrorIsRethrownAfterTheEarlierFrames) {
  const TempDir dir("neopipe_run_stream_sink_error");
  write_sequence(dir, disc_frames(8, {32, 24}, 34));
  auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
  pl::RunStats stats;
  std::vector<std::int64_t> delivered;
  try {
    pl::run_stream(
        *source, pl::compile(pl::blob_graph(), pl::standard_kernels()), {},
        [&](const pl::FrameResult& r) {
          if (r.index == 4) throw std::runtime_error("disk full");
          delivered.push_back(r.index);
        },
        stats);
    ADD_FAILURE() << "the sink's error was lost";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "disk full");
  }
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1, 2, 3}));
}

// A sink that threw receives nothing more, however many frames were in flight (regression: the
// clean-up's finish() used to go on delivering frames 5, 6, ... to a sink that failed on frame 4,
// leaving a hole in its output). Repeated because how many frames are in flight varies.
TEST(RunStream, FailedSinkReceivesNoLaterFrames) {
  const TempDir dir("neopipe_run_stream_failed_sink");
  write_sequence(dir, disc_frames(16, {32, 24}, 35));
  for (int attempt = 0; attempt < 10; ++attempt) {
    auto source = io::open_frame_source({dir.str()}, io::ColorFormat::bgr);
    pl::RunStats stats;
    std::vector<std::int64_t> delivered;
    pl::StreamOptions options;
    options.executor = {.threads = 2, .frames_in_flight = 6};
    EXPECT_THROW(pl::run_stream(
                     *source, pl::compile(pl::blob_graph(), pl::standard_kernels()), options,
                     [&](const pl::FrameResult& r) {
                       delivered.push_back(r.index);
                       if (r.index == 4) throw std::runtime_error("disk full");
                     },
                     stats),
                 std::runtime_error);
    EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1, 2, 3, 4})) << "attempt " << attempt;
  }
}

TEST(RunStream, RealtimeModeCountsEveryFrameReadAsProcessedOrDropped) {
  const TempDir dir("neopipe_run_stream_realtime");
  const int n = 20;
  std::vector<cv::Mat> frames;
  for (int i = 0; i < n; ++i) frames.emplace_back(12, 16, CV_8UC1, cv::Scalar(i * 10));
  write_sequence(dir, frames);

  auto progress = std::make_shared<ReadProgress>();
  pl::KernelRegistry registry = pl::standard_kernels();
  registry.add({"hold_first", "copies; holds its first frame until 6 frames were read",
                [progress](pl::NodeContext&) { return std::make_unique<HoldFirstFrameNode>(progress, 6); }});
  pl::CompiledGraph graph = pl::compile(pl::parse_graph_spec("nodes:\n"
                                                             "  - {name: src, kernel: source, params: {format: gray}}\n"
                                                             "  - {name: hold, kernel: hold_first, inputs: {in: src}}\n"
                                                             "outputs: hold\n",
                                                             "realtime.yaml"),
                                        registry);
  CountingSource source(io::open_frame_source({dir.str()}, io::ColorFormat::gray), progress);
  pl::StreamOptions options;
  options.realtime = true;
  options.fps = 1000;
  options.executor = {.threads = 2, .frames_in_flight = 2};
  pl::RunStats stats;
  std::vector<std::int64_t> indices;
  pl::run_stream(
      source, std::move(graph), options,
      [&](const pl::FrameResult& r) {
        indices.push_back(r.index);
        // Each result is its own frame, unchanged by the node.
        EXPECT_EQ(std::get<cv::Mat>(r.outputs.at(0)).at<std::uint8_t>(0, 0), r.index * 10);
      },
      stats);

  EXPECT_EQ(stats.frames_read, n);
  EXPECT_EQ(stats.frames_read, stats.frames_processed + stats.frames_dropped);
  // Frame 0 is held until frame 5 has been read; frame 1 takes the second slot, so frames 2, 3 and 4
  // find the pipeline full and must have been dropped.
  EXPECT_GE(stats.frames_dropped, 3);
  EXPECT_GE(stats.frames_processed, 2);
  EXPECT_EQ(static_cast<std::int64_t>(indices.size()), stats.frames_processed);
  EXPECT_EQ(stats.latency.count(), static_cast<std::int64_t>(indices.size()));
  for (size_t i = 1; i < indices.size(); ++i) EXPECT_LT(indices[i - 1], indices[i]);
  EXPECT_EQ(stats.blobs, 0);  // the graph has no blob output
  EXPECT_TRUE(stats.realtime);
}

TEST(BlobsNode, TallFramesLabelledInStripesEqualOnePass) {
  // Frames of 1024 rows or more are labelled in parallel stripes and joined: the table must be the
  // kernel's single pass, bit for bit, for every thread count (components cross the stripe borders).
  cv::RNG rng(17);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 3; ++i) {
    cv::Mat f(1080, 333, CV_8UC1);  // two stripes of 540 rows on 2+ threads
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(f, f, {9, 9}, 3.0);
    frames.push_back(f);
  }
  const auto spec = pl::blob_graph({.threshold = 127, .connectivity = 8, .source = pl::PortType::gray8});
  for (int threads : {1, 2, 3, 8}) {
    const auto results = pl::run_frames(pl::compile(spec, pl::standard_kernels()), frames, {.threads = threads});
    for (size_t f = 0; f < frames.size(); ++f) {
      neopipe::kernels::BlobParams p;
      p.threshold = 127;
      const auto expected = neopipe::kernels::extract_blobs(frames[f], p, frames[f]);
      expect_same_blobs(std::get<pl::BlobList>(results[f].outputs.at(0)), expected,
                        "threads " + std::to_string(threads) + ", frame " + std::to_string(f));
    }
  }
}
