#include "bench/blob_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "bench/halide_peer.hpp"
#include "bench/memory.hpp"
#include "bench/peers.hpp"
#include "bench/synthetic.hpp"
#include "bench/timing.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/kernel_registry.hpp"

namespace neopipe::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Frames {
  std::vector<cv::Mat> images;
  int threshold = 0;
};

// The graph neopipe runs for the case; for the built-in cases its output 0 is the blob table.
pipeline::CompiledGraph case_graph(const BenchCase& c, int threshold) {
  const std::string& name = c.name;
  if (c.graph) return pipeline::compile(*c.graph, pipeline::standard_kernels());
  if (name == "chain") return pipeline::compile(chain_graph(threshold), pipeline::standard_kernels());
  pipeline::BlobGraphOptions o;
  o.threshold = threshold;
  o.source = pipeline::PortType::gray8;
  return pipeline::compile(pipeline::blob_graph(o), pipeline::standard_kernels());
}

// A user's graph reads gray or BGR frames: the dots frames, converted where it reads colour.
cv::Mat in_source_format(const BenchCase& c, cv::Mat gray) {
  if (!c.graph) return gray;
  const auto type = case_graph(c, 0).source_type();
  if (type == pipeline::PortType::gray8) return gray;
  if (type == pipeline::PortType::bgr8) {
    cv::Mat bgr;
    cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
    return bgr;
  }
  throw std::invalid_argument(c.graph->origin + ": its source reads " + std::string(pipeline::to_string(type)) +
                              " frames; neopipe bench generates gray or bgr frames");
}

Frames make_frames(const BenchCase& c, int n) {
  Frames f;
  for (int i = 0; i < n; ++i) {
    const auto seed = 1000 * static_cast<std::uint64_t>(i) + 17;
    f.images.push_back(in_source_format(c, uses_dots_frames(c.name) ? make_dots_frame(c.size, c.blobs, seed, c.radius)
                                                                    : make_dense_frame(c.size, seed)));
  }
  f.threshold = uses_dots_frames(c.name) ? dots_threshold : dense_threshold(f.images.front());
  return f;
}

// The first blob table among a frame's outputs, if the graph has one.
const pipeline::BlobList* first_blob_list(const std::vector<pipeline::Value>& outputs) {
  for (const auto& v : outputs) {
    if (const auto* blobs = std::get_if<pipeline::BlobList>(&v)) return blobs;
  }
  return nullptr;
}

// The case the OpenCV way: the number of blobs and their summed area.
class OpenCvCase {
 public:
  explicit OpenCvCase(const std::string& name) : is_chain_(name == "chain") {}
  int operator()(const cv::Mat& gray, int threshold) {
    return is_chain_ ? chain_(gray, threshold) : blobs_(gray, threshold);
  }
  std::int64_t total_area() const { return is_chain_ ? chain_.total_area() : blobs_.total_area(); }

 private:
  bool is_chain_;
  OpenCvBlobs blobs_;
  OpenCvChain chain_;
};

// Frames per second of `one(i)` called on frames i = 0, 1, 2, ... for at least min_seconds.
template <class F>
double time_loop(F&& one, double min_seconds) {
  for (int i = 0; i < 3; ++i) one(i);  // warm caches and allocations
  std::int64_t n = 0;
  const auto t0 = Clock::now();
  double s = 0;
  do {
    for (int k = 0; k < 8; ++k) one(static_cast<int>(n++));
    s = seconds_since(t0);
  } while (s < min_seconds);
  return static_cast<double>(n) / s;
}

double time_neopipe(const BenchCase& c, const Frames& f, double min_seconds) {
  std::int64_t blobs = 0;  // results are looked at, as a user's handler would
  pipeline::ExecutorOptions eo;
  eo.threads = c.threads;
  pipeline::Executor ex(case_graph(c, f.threshold), eo, [&](pipeline::FrameResult&& r) {
    if (const auto* list = first_blob_list(r.outputs)) blobs += static_cast<std::int64_t>(list->size());
  });
  const auto n_frames = static_cast<std::int64_t>(f.images.size());
  std::int64_t i = 0;
  for (; i < 3; ++i) ex.submit(i, f.images[static_cast<size_t>(i % n_frames)]);
  ex.finish();
  const std::int64_t start = i;
  const auto t0 = Clock::now();
  do {
    for (int k = 0; k < 8; ++k, ++i) ex.submit(i, f.images[static_cast<size_t>(i % n_frames)]);
  } while (seconds_since(t0) < min_seconds);
  ex.finish();
  return static_cast<double>(i - start) / seconds_since(t0);
}

// The Halide composite streamed as the executor is: frames submitted one after another.
double time_halide(const Frames& f, int threads, double min_seconds) {
  HalideChain chain(threads);
  const auto n_frames = static_cast<std::int64_t>(f.images.size());
  std::int64_t i = 0;
  for (; i < 3; ++i) chain.submit(f.images[static_cast<size_t>(i % n_frames)], f.threshold);
  chain.finish();
  const std::int64_t start = i;
  const auto t0 = Clock::now();
  do {
    for (int k = 0; k < 8; ++k, ++i) chain.submit(f.images[static_cast<size_t>(i % n_frames)], f.threshold);
  } while (seconds_since(t0) < min_seconds);
  chain.finish();
  return static_cast<double>(i - start) / seconds_since(t0);
}

bool same_blobs(const pipeline::BlobList& a, const pipeline::BlobList& b) {
  const auto same = [](const kernels::Blob& p, const kernels::Blob& q) {
    return p.area == q.area && p.x0 == q.x0 && p.y0 == q.y0 && p.width == q.width && p.height == q.height &&
           p.cx == q.cx && p.cy == q.cy && p.wcx == q.wcx && p.wcy == q.wcy && p.mu20 == q.mu20 && p.mu11 == q.mu11 &&
           p.mu02 == q.mu02;
  };
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), same);
}

// Runs `timed` (which returns frames/s); on the first repeat also notes how far the resident set
// grew while it ran.
template <class F>
double timed_with_memory(F&& timed, bool first, std::optional<double>& growth_mib) {
  if (!first) return timed();
  const PeakGrowth peak;
  const double fps = timed();
  if (const auto g = peak.growth()) growth_mib = static_cast<double>(*g) / (1024.0 * 1024.0);
  return fps;
}

}  // namespace

bool has_halide_peer(const std::string& case_name) {
  return case_name == "chain" && halide_available();
}

bool uses_dots_frames(const std::string& case_name) {
  return case_name == "dots" || case_name == "chain" || case_name == graph_case_name;
}

pipeline::GraphSpec chain_graph(int threshold) {
  pipeline::GraphBuilder b("<bench chain graph>");
  b.node("src", "source", "{format: gray}")
      .node("smooth", "conv3x3", "{preset: smooth}")
      .node("binary", "threshold", "{value: " + std::to_string(threshold) + "}")
      .node("eroded", "bool3x3", "{op: erode}")
      .node("opened", "bool3x3", "{op: dilate}")
      .node("blobs", "blobs", "{threshold: 0, connectivity: 8}")
      .connect("src", "smooth.in")
      .connect("smooth", "binary.in")
      .connect("binary", "eroded.in")
      .connect("eroded", "opened.in")
      .connect("opened", "blobs.in")
      .connect("src", "blobs.weights")
      .output("blobs");
  return b.spec();
}

std::vector<BenchRecord> run_blob_bench(const BenchCase& c, const BenchOptions& o) {
  const Frames f = make_frames(c, std::max(o.distinct_frames, 1));
  const auto n = static_cast<int>(f.images.size());
  const auto frame = [&](int i) -> const cv::Mat& { return f.images[static_cast<size_t>(i % n)]; };

  std::vector<double> np;
  std::vector<double> cvv;
  std::vector<double> fl;
  std::vector<double> hl;
  std::optional<double> hl_mem;
  std::optional<double> np_mem;
  std::optional<double> cv_mem;
  std::optional<double> fl_mem;
  const int saved_cv_threads = cv::getNumThreads();
  cv::setNumThreads(c.threads);
  OpenCvCase opencv(c.name);
  const bool has_opencv = !c.graph;
  ReadFloor floor(c.threads);
  // Interleave the implementations so a slow spell of the machine hits all of them alike.
  for (int r = 0; r < std::max(o.repeats, 1); ++r) {
    const bool first = r == 0;
    np.push_back(timed_with_memory([&] { return time_neopipe(c, f, o.min_seconds); }, first, np_mem));
    if (has_opencv) {
      cvv.push_back(timed_with_memory(
          [&] { return time_loop([&](int i) { opencv(frame(i), f.threshold); }, o.min_seconds); }, first, cv_mem));
    }
    fl.push_back(
        timed_with_memory([&] { return time_loop([&](int i) { floor(frame(i)); }, o.min_seconds); }, first, fl_mem));
    if (has_halide_peer(c.name)) {
      hl.push_back(timed_with_memory([&] { return time_halide(f, c.threads, o.min_seconds); }, first, hl_mem));
    }
  }
  cv::setNumThreads(saved_cv_threads);
  const double pixels = c.size.area();
  std::vector<BenchRecord> out;
  for (const auto& [impl, v, mem] : {std::tuple{"neopipe", &np, np_mem}, std::tuple{"opencv", &cvv, cv_mem},
                                     std::tuple{"floor", &fl, fl_mem}, std::tuple{"halide", &hl, hl_mem}}) {
    if (v->empty()) continue;
    const double fps = median(*v);
    out.push_back(
        {c.name, impl, c.size.width, c.size.height, c.threads, fps, fps * pixels / 1e6, 1e9 / (fps * pixels), mem});
  }
  return out;
}

CrossCheck cross_check(const BenchCase& c) {
  const Frames f = make_frames(c, 1);
  const auto results = pipeline::run_frames(case_graph(c, f.threshold), {f.images.front()}, {});
  if (c.graph) {
    const auto* list = first_blob_list(results.front().outputs);
    return {list ? static_cast<std::int64_t>(list->size()) : -1, {}};
  }
  const auto& ours = std::get<pipeline::BlobList>(results.front().outputs[0]);
  std::int64_t our_area = 0;
  for (const auto& b : ours) our_area += b.area;
  OpenCvCase opencv(c.name);
  const auto theirs = static_cast<std::int64_t>(opencv(f.images.front(), f.threshold));
  const std::int64_t their_area = opencv.total_area();
  CrossCheck check;
  check.blobs = static_cast<std::int64_t>(ours.size());
  if (check.blobs != theirs || our_area != their_area) {
    check.mismatch = c.name + " " + std::to_string(c.size.width) + "x" + std::to_string(c.size.height) +
                     ": neopipe found " + std::to_string(check.blobs) + " blobs (" + std::to_string(our_area) +
                     " pixels), OpenCV " + std::to_string(theirs) + " (" + std::to_string(their_area) + " pixels)";
  }
  if (check.mismatch.empty() && has_halide_peer(c.name)) {
    HalideChain halide(1);
    if (!same_blobs(ours, halide(f.images.front(), f.threshold))) {
      check.mismatch = c.name + " " + std::to_string(c.size.width) + "x" + std::to_string(c.size.height) +
                       ": the Halide composite's blob table differs from neopipe's";
    }
  }
  return check;
}

}  // namespace neopipe::bench
