#include "apps/bench_command.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <optional>
#include <regex>
#include <set>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "apps/run_command.hpp"
#include "bench/blob_bench.hpp"
#include "bench/memory.hpp"
#include "bench/video_bench.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::apps {
namespace {

// Keys in the order written: the metadata first, then the records, each record's keys as documented.
using BenchJson = nlohmann::ordered_json;

const std::vector<cv::Size> kDefaultSizes{{256, 256}, {640, 480}, {1920, 1080}};
const std::vector<cv::Size> kSweepSizes{{160, 120}, {320, 240}, {640, 480}, {1280, 720}, {1920, 1080}, {3840, 2160}};
const std::vector<int> kSweepBlobs{10, 30, 100, 300, 1000, 3000, 10000};
const cv::Size kBlobSweepSize{1920, 1080};
constexpr double kBlobSweepRadius = 3;
// A blob-sweep point whose frame holds fewer disks than this share of the count asked for is left
// out (with a note): the frame is full, and the row would repeat the one before.
constexpr double kBlobSweepFill = 0.9;

cv::Size parse_frame_size(const std::string& s) {
  static const std::regex kSize(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, kSize)) throw UsageError{"--size " + s + ": expected WxH, e.g. 640x480"};
  const cv::Size size(std::stoi(m[1]), std::stoi(m[2]));
  if (size.width < 16 || size.height < 16) throw UsageError{"--size " + s + ": at least 16x16"};
  return size;
}

std::string size_text(cv::Size s) {
  return fmt::format("{}x{}", s.width, s.height);
}

// --scaling: every count up to 8 hardware threads, beyond that powers of two and the maximum.
std::vector<int> scaling_threads(int all) {
  std::vector<int> t;
  for (int i = 1; i < all; i = all <= 8 ? i + 1 : i * 2) t.push_back(i);
  t.push_back(all);
  return t;
}

std::vector<int> thread_counts(const BenchArgs& a, int all) {
  if (a.scaling) return scaling_threads(all);
  std::vector<int> t = a.threads.empty() ? std::vector<int>{1, all} : a.threads;
  std::vector<int> unique;  // in the order given, each once
  for (const int n : t) {
    if (std::find(unique.begin(), unique.end(), n) == unique.end()) unique.push_back(n);
  }
  return unique;
}

// One case at one size and blob count, cross-checked, to be timed at each thread count.
struct Point {
  bench::BenchCase c;  // threads unset
  std::int64_t blobs_found = 0;
};

struct Plan {
  std::vector<Point> points;
  std::vector<int> threads;
  std::string sweep;               // "", "size" or "blobs"
  std::vector<std::string> notes;  // sweep points left out, and why
};

// The points to measure; every one cross-checked. Throws UsageError for a bad combination and
// std::runtime_error when neopipe and OpenCV disagree.
Plan make_plan(const BenchArgs& a, int all) {
  Plan plan;
  plan.sweep = a.sweep;
  plan.threads = thread_counts(a, all);
  std::vector<cv::Size> sizes;
  for (const auto& s : a.sizes) sizes.push_back(parse_frame_size(s));
  std::vector<std::string> cases = a.cases;
  std::shared_ptr<const pipeline::GraphSpec> graph;
  if (!a.graph.empty()) {
    if (a.sweep == "blobs") throw UsageError{"--sweep blobs compares built-in cases; time --graph with --sweep size"};
    graph = std::make_shared<const pipeline::GraphSpec>(pipeline::load_graph_spec(a.graph));
    // Its errors now, not after minutes of timing.
    const auto compiled = pipeline::compile(*graph, pipeline::standard_kernels());
    plan.notes.push_back(fmt::format("case graph = {}, on the dots frames read as {}", a.graph,
                                     pipeline::to_string(compiled.source_type())));
  }
  if (cases.empty() && graph == nullptr && (a.video.empty() || !a.sweep.empty())) {
    cases = a.sweep.empty() ? bench::case_names : std::vector<std::string>{"dots"};
  }
  const auto check = [&](const bench::BenchCase& c) {
    const auto result = bench::cross_check(c);
    if (!result.mismatch.empty()) {
      throw std::runtime_error("results disagree, so timing them means nothing: " + result.mismatch);
    }
    return result.blobs;
  };
  if (a.sweep == "blobs") {
    if (sizes.size() > 1)
      throw UsageError{"--sweep blobs runs at one --size; " + std::to_string(sizes.size()) + " given"};
    const cv::Size size = sizes.empty() ? kBlobSweepSize : sizes.front();
    for (const auto& name : cases) {
      if (!bench::uses_dots_frames(name)) {
        throw UsageError{"--sweep blobs: case " + name + " has no blob count to vary (use --case dots or chain)"};
      }
      for (const int count : kSweepBlobs) {
        const bench::BenchCase c{name, size, 0, count, kBlobSweepRadius, nullptr};
        const std::int64_t found = check(c);
        if (static_cast<double>(found) < kBlobSweepFill * count) {
          plan.notes.push_back(
              fmt::format("{}: {} disks of radius {} do not fit in {} (only {}); the sweep stops there", name, count,
                          kBlobSweepRadius, size_text(size), found));
          break;
        }
        plan.points.push_back({c, found});
      }
    }
    return plan;
  }
  if (sizes.empty()) sizes = a.sweep == "size" ? kSweepSizes : kDefaultSizes;
  for (const auto& name : cases) {
    for (const auto& s : sizes) {
      const bench::BenchCase c{name, s, 0, 100, 0, nullptr};
      plan.points.push_back({c, check(c)});
    }
  }
  if (graph) {
    for (const auto& s : sizes) {
      const bench::BenchCase c{bench::graph_case_name, s, 0, 100, 0, graph};
      plan.points.push_back({c, check(c)});
    }
  }
  return plan;
}

std::string ratio(double a, double b) {
  return b > 0 ? fmt::format("{:.2f}x", a / b) : std::string("-");
}

std::string mib(const std::optional<double>& v) {
  return v ? fmt::format("{:.1f}", *v) : std::string("-");
}

BenchJson nullable(const std::optional<double>& v) {
  return v ? BenchJson(*v) : BenchJson(nullptr);
}

// The measurements of one point at one thread count, by implementation.
struct Row {
  const Point* point;
  int threads;
  std::map<std::string, bench::BenchRecord> by_impl;
};

void print_header(const Plan& plan) {
  if (plan.sweep == "size") {
    fmt::print("sweep: frame size; dots frames with about 100 disks of radius min(w, h) / 80\n");
  } else if (plan.sweep == "blobs") {
    fmt::print("sweep: blob count; dots frames with disks of radius {} at {}\n", kBlobSweepRadius,
               plan.points.empty() ? std::string("?") : size_text(plan.points.front().c.size));
  }
  fmt::print("{:<6} {:>10} {:>6} {:>7} {:>11} {:>11} {:>11} {:>11} {:>8} {:>8} {:>9} {:>9} {:>8} {:>7} {:>7}\n", "case",
             "size", "blobs", "threads", "neopipe f/s", "opencv f/s", "halide f/s", "floor f/s", "np ns/px", "cv ns/px",
             "vs opencv", "vs halide", "floor/np", "np +MiB", "cv +MiB");
}

// A record of the row, or nullptr where the case has no such implementation (halide beside
// everything but the chain; opencv beside a user's graph).
const bench::BenchRecord* record_of(const Row& r, const std::string& impl) {
  const auto it = r.by_impl.find(impl);
  return it == r.by_impl.end() ? nullptr : &it->second;
}

std::string fps_text(const bench::BenchRecord* r) {
  return r ? fmt::format("{:.1f}", r->fps) : std::string("-");
}

std::string blobs_text(std::int64_t blobs) {
  return blobs < 0 ? std::string("-") : std::to_string(blobs);
}

void print_row(const Row& r) {
  const auto& np = r.by_impl.at("neopipe");
  const auto& fl = r.by_impl.at("floor");
  const auto* cv = record_of(r, "opencv");
  const auto* hl = record_of(r, "halide");
  fmt::print(
      "{:<6} {:>10} {:>6} {:>7} {:>11.1f} {:>11} {:>11} {:>11.1f} {:>8.2f} {:>8} {:>9} {:>9} {:>8} {:>7} {:>7}\n",
      r.point->c.name, size_text(r.point->c.size), blobs_text(r.point->blobs_found), r.threads, np.fps, fps_text(cv),
      fps_text(hl), fl.fps, np.ns_per_pixel, cv ? fmt::format("{:.2f}", cv->ns_per_pixel) : std::string("-"),
      cv ? ratio(np.fps, cv->fps) : "-", hl ? ratio(np.fps, hl->fps) : "-", ratio(fl.fps, np.fps),
      mib(np.rss_growth_mib), cv ? mib(cv->rss_growth_mib) : "-");
}

// f/s at N threads over f/s at 1 thread, for every point measured at 1 thread and at more.
void print_scaling(const std::vector<Row>& rows) {
  std::map<const Point*, const Row*> one;
  for (const auto& r : rows) {
    if (r.threads == 1) one[r.point] = &r;
  }
  bool header = false;
  for (const auto& r : rows) {
    const auto base = one.find(r.point);
    if (r.threads == 1 || base == one.end()) continue;
    if (!header) {
      fmt::print("\nthread scaling: f/s at N threads / f/s at 1 thread\n");
      fmt::print("{:<6} {:>10} {:>6} {:>7} {:>8} {:>8}\n", "case", "size", "blobs", "threads", "neopipe", "opencv");
      header = true;
    }
    const auto* cv = record_of(r, "opencv");
    const auto* cv1 = record_of(*base->second, "opencv");
    fmt::print("{:<6} {:>10} {:>6} {:>7} {:>8} {:>8}\n", r.point->c.name, size_text(r.point->c.size),
               blobs_text(r.point->blobs_found), r.threads,
               ratio(r.by_impl.at("neopipe").fps, base->second->by_impl.at("neopipe").fps),
               cv && cv1 ? ratio(cv->fps, cv1->fps) : "-");
  }
}

BenchJson record_json(const bench::BenchRecord& r, const Plan& plan, const Point& p) {
  return {{"case", r.case_name},
          {"impl", r.impl},
          {"graph", p.c.graph ? BenchJson(p.c.graph->origin) : BenchJson(nullptr)},
          {"sweep", plan.sweep.empty() ? BenchJson(nullptr) : BenchJson(plan.sweep)},
          {"width", r.width},
          {"height", r.height},
          {"blobs", p.blobs_found < 0 ? BenchJson(nullptr) : BenchJson(p.blobs_found)},
          {"threads", r.threads},
          {"fps", r.fps},
          {"mpix_s", r.mpix_s},
          {"ns_per_pixel", r.ns_per_pixel},
          {"rss_growth_mib", nullable(r.rss_growth_mib)}};
}

BenchJson video_json(const bench::VideoRecord& r, const bench::VideoInfo& v) {
  const double pixels = v.size.area();
  return {{"case", "video"},
          {"impl", r.impl},
          {"file", v.path},
          {"width", v.size.width},
          {"height", v.size.height},
          {"frames", v.frames ? BenchJson(*v.frames) : BenchJson(nullptr)},
          {"threads", r.threads},
          {"fps", r.fps},
          {"mpix_s", r.fps * pixels / 1e6},
          {"ns_per_pixel", 1e9 / (r.fps * pixels)}};
}

}  // namespace

CLI::App* add_bench_command(CLI::App& parent, BenchArgs& a) {
  CLI::App* cmd = parent.add_subcommand(
      "bench",
      "Measure neopipe graphs against the same work as OpenCV calls and a memory-read floor, on generated frames "
      "or a video");
  cmd->footer(
      "Cases (generated frames; the implementations run in the same process, interleaved, on the same frames):\n"
      "  dots   about 100 small bright disks on a dark noisy background. neopipe: its built-in blob graph\n"
      "         (threshold -> blobs) at a fixed threshold; opencv: cv::threshold + cv::connectedComponentsWithStats.\n"
      "  dense  smoothed noise thresholded at its mean: many large irregular components; the same two programs.\n"
      "  chain  the dots frames through 3x3 smooth -> threshold -> 3x3 opening (erode, dilate) -> blobs; opencv:\n"
      "         cv::GaussianBlur 3x3 -> cv::threshold -> cv::morphologyEx MORPH_OPEN 3x3 -> "
      "connectedComponentsWithStats.\n"
      "  halide (chain only, when built with Halide 14) the composite a Halide user would write: the four iconic\n"
      "         stages in Halide (ahead-of-time, strips of 32 rows in parallel, every stage per strip, vectorised),\n"
      "         then neopipe's own blob stage, the next frame's Halide stages overlapping this frame's blobs.\n"
      "  floor  (in every case) one pass summing every pixel: the cost of looking at each pixel once.\n"
      "  graph  (--graph G.yaml) your own graph through the executor on the dots frames (converted to BGR if it\n"
      "         reads colour), against the floor; no OpenCV column (there is no general translation). Without\n"
      "         --case, only the graph is timed; blobs = its first blob output's count on the first frame.\n"
      "Before timing, every case and size is cross-checked: neopipe and OpenCV must find the same blobs (count\n"
      "and total area), and the Halide composite exactly neopipe's blob table, else the bench stops with an error.\n"
      "Sweeps (case dots unless --case says otherwise):\n"
      "  --sweep size   frame sizes 160x120 .. 3840x2160 (or --size's), about 100 disks: how cost grows with pixels\n"
      "  --sweep blobs  10 .. 10000 disks of radius 3 at one size (--size, default 1920x1080): how cost grows with\n"
      "                 blobs; counts that no longer fit in the frame are left out\n"
      "Columns: blobs = blobs in the case's first frame (both found the same); f/s = frames per second, the\n"
      "median of --repeats runs; ns/px = nanoseconds per pixel (np neopipe, cv OpenCV); vs opencv = neopipe f/s\n"
      "/ opencv f/s; vs halide = neopipe f/s / halide f/s; floor/np = floor f/s / neopipe f/s; np +MiB, cv +MiB = how "
      "far the resident memory rose\n"
      "while neopipe / OpenCV ran (their buffers, frames in flight, thread stacks; - if the system cannot tell).\n"
      "With several thread counts including 1, a thread scaling table follows: f/s at N threads / f/s at 1.\n"
      "The footer gives the process's peak resident memory (VmHWM).\n"
      "--video FILE: cv decode f/s = the file read by cv::VideoCapture into BGR frames and nothing else (the\n"
      "decode-only reference); decode f/s = the same with neopipe's video reader, in the format the graph reads\n"
      "(gray: the decoder's luma plane); run f/s = `neopipe run FILE`'s default graph (gray -> Otsu threshold ->\n"
      "blobs) through the engine, results discarded; run+csv f/s = the same writing its CSV blob table (to\n"
      "nowhere: the formatting without a disk); run/cv decode, run+csv/cv decode and run/decode = their ratios\n"
      "(1.00x: as fast as decoding alone). The four run interleaved; a note says when the timed runs were\n"
      "shorter than the video (its first frames only) and which --min-time covers it. Without --case or\n"
      "--sweep, --video measures only the video.\n"
      "--json prints one JSON object instead of the tables: {\"records\": [...], \"peak_rss_mib\": ..., ...}\n"
      "(docs/formats.md). A mismatch, a missing or undecodable video exit 1; a bad command line exits 2.");
  cmd->add_option("--size", a.sizes, "Frame size(s) (default: 256x256 640x480 1920x1080)")->type_name("WxH");
  auto* threads = cmd->add_option("--threads", a.threads, "Thread count(s), e.g. 1 or 1,2,4 (default: 1 and all)")
                      ->check(CLI::Range(1, 256))
                      ->delimiter(',');
  cmd->add_flag("--scaling", a.scaling, "Thread counts 1, 2, ... up to all hardware threads (powers of two above 8)")
      ->excludes(threads);
  cmd->add_option("--case", a.cases, "Case(s) to run (default: dots dense chain)")
      ->check(CLI::IsMember(bench::case_names))
      ->delimiter(',');
  cmd->add_option("--sweep", a.sweep, "Sweep frame size or blob count instead of the --size list")
      ->check(CLI::IsMember({"size", "blobs"}));
  cmd->add_option("--graph", a.graph, "Also time this graph spec (YAML) on the dots frames against the read floor")
      ->type_name("G.yaml");
  cmd->add_option("--video", a.video, "Also measure this video: decode-only f/s (OpenCV, neopipe) vs `neopipe run` f/s")
      ->type_name("FILE");
  cmd->add_flag("--json", a.json, "Print one JSON object (records, peak memory) instead of the tables");
  cmd->add_option("--min-time", a.min_seconds, "Seconds each timed run lasts at least")->check(CLI::Range(0.01, 60.0));
  cmd->add_option("--repeats", a.repeats, "Timed runs per measurement; the median is reported (default: 5)")
      ->check(CLI::Range(1, 100));
  return cmd;
}

int bench_command(const BenchArgs& a) {
  const int all = tbb::info::default_concurrency();
  bench::BenchOptions o;
  o.min_seconds = a.min_seconds;
  o.repeats = a.repeats;

  // Everything that can fail on bad input fails here, before minutes of timing.
  std::optional<bench::VideoInfo> video;
  pipeline::GraphSpec video_graph;
  auto video_format = pipeline::io::ColorFormat::bgr;
  if (!a.video.empty()) {
    video_graph = run_graph(RunArgs{});
    video_format = run_source_format(pipeline::compile(video_graph, pipeline::standard_kernels()));
    video = bench::probe_video(a.video, video_format);
  }
  const Plan plan = make_plan(a, all);

  const auto steps =
      static_cast<std::int64_t>(plan.points.size() * plan.threads.size() + (video ? plan.threads.size() : 0));
  BenchJson records = BenchJson::array();
  std::vector<Row> rows;
  rows.reserve(plan.points.size() * plan.threads.size());
  if (!a.json) {
    fmt::print("neopipe bench: median of {} run(s) of >= {:.2f} s each; {} hardware threads; OpenCV {}\n", o.repeats,
               o.min_seconds, all, CV_VERSION);
    for (const auto& n : plan.notes) fmt::print("note: {}\n", n);
    if (!plan.points.empty()) print_header(plan);
    std::fflush(stdout);
  }
  ProgressBar bar("neopipe bench", steps, a.json);
  std::int64_t done = 0;
  for (const auto& p : plan.points) {
    for (const int t : plan.threads) {
      bar.update(done++, fmt::format("{} {} {} threads", p.c.name, size_text(p.c.size), t));
      bench::BenchCase c = p.c;
      c.threads = t;
      Row row{&p, t, {}};
      for (auto& r : bench::run_blob_bench(c, o)) {
        records.push_back(record_json(r, plan, p));
        row.by_impl.emplace(r.impl, std::move(r));
      }
      rows.push_back(std::move(row));
      if (!a.json) {
        bar.clear();
        print_row(rows.back());
        std::fflush(stdout);
      }
    }
  }
  if (!a.json) print_scaling(rows);

  std::vector<std::string> video_notes;
  if (video) {
    if (!a.json) {
      if (!plan.points.empty()) fmt::print("\n");
      fmt::print("video {}: {}, {} frames{}; `neopipe run`'s default graph\n", video->path, size_text(video->size),
                 video->frames ? std::to_string(*video->frames) : std::string("?"),
                 video->fps > 0 ? fmt::format(" at {:.4g} f/s", video->fps) : std::string());
      fmt::print(
          "cv decode: cv::VideoCapture reading BGR; decode: neopipe's reader, {} frames; run: results discarded;\n"
          "run+csv: the CSV blob table formatted too, as `neopipe run --out t.csv` writes it\n",
          video_format == pipeline::io::ColorFormat::gray ? "gray" : "BGR");
      fmt::print("{:>7} {:>14} {:>11} {:>11} {:>12} {:>13} {:>17} {:>10}\n", "threads", "cv decode f/s", "decode f/s",
                 "run f/s", "run+csv f/s", "run/cv decode", "run+csv/cv decode", "run/decode");
      std::fflush(stdout);
    }
    double slowest = 0;  // f/s of the slowest implementation at any thread count
    for (const int t : plan.threads) {
      bar.update(done++, fmt::format("video {} threads", t));
      std::map<std::string, double> fps;
      for (const auto& r : bench::run_video_bench(video->path, video_graph, video_format, t, o)) {
        fps[r.impl] = r.fps;
        if (r.fps > 0 && (slowest == 0 || r.fps < slowest)) slowest = r.fps;
        records.push_back(video_json(r, *video));
      }
      if (!a.json) {
        bar.clear();
        fmt::print("{:>7} {:>14.1f} {:>11.1f} {:>11.1f} {:>12.1f} {:>13} {:>17} {:>10}\n", t, fps["opencv_decode"],
                   fps["decode"], fps["run"], fps["run_csv"], ratio(fps["run"], fps["opencv_decode"]),
                   ratio(fps["run_csv"], fps["opencv_decode"]), ratio(fps["run"], fps["decode"]));
        std::fflush(stdout);
      }
    }
    // A timed run that ends before the video does measures its first frames only, with opening the
    // file and starting the threads in every timing: noisier, and not the whole file's rate.
    if (video->frames && slowest > 0 && static_cast<double>(*video->frames) / slowest > o.min_seconds) {
      const double pass = static_cast<double>(*video->frames) / slowest;
      std::string note = fmt::format(
          "the timed runs covered about the first {} of the video's {} frames; --min-time {:.1f} would make each "
          "a whole pass",
          static_cast<std::int64_t>(slowest * o.min_seconds), *video->frames, std::ceil(pass * 12) / 10);
      if (!a.json) fmt::print("note: {}\n", note);
      video_notes.push_back(std::move(note));
    }
  }
  bar.clear();

  const auto peak = bench::peak_rss_bytes();
  const std::optional<double> peak_mib =
      peak ? std::optional<double>(static_cast<double>(*peak) / (1024.0 * 1024.0)) : std::nullopt;
  if (a.json) {
    // Built before the object, not inside its initializer list, where GCC 12 warns of a
    // maybe-uninitialized optional (a false positive of its inlining).
    const BenchJson peak_json = nullable(peak_mib);
    std::vector<std::string> notes = plan.notes;
    notes.insert(notes.end(), video_notes.begin(), video_notes.end());
    const BenchJson out{{"opencv_version", CV_VERSION},
                        {"hardware_threads", all},
                        {"repeats", o.repeats},
                        {"min_time_s", o.min_seconds},
                        {"peak_rss_mib", peak_json},
                        {"notes", notes},
                        {"records", records}};
    std::cout << out.dump(2) << '\n';
  } else {
    fmt::print("\npeak resident memory of this process: {} MiB\n", mib(peak_mib));
  }
  return kExitOk;
}

}  // namespace neopipe::apps
