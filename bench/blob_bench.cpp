#include "bench/blob_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <opencv2/core.hpp>

#include "bench/peers.hpp"
#include "bench/synthetic.hpp"
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

Frames make_frames(const BenchCase& c, int n) {
  Frames f;
  for (int i = 0; i < n; ++i) {
    const auto seed = 1000 * static_cast<std::uint64_t>(i) + 17;
    f.images.push_back(c.name == "dots" ? make_dots_frame(c.size, 100, seed) : make_dense_frame(c.size, seed));
  }
  f.threshold = c.name == "dots" ? dots_threshold : dense_threshold(f.images.front());
  return f;
}

pipeline::CompiledGraph blob_graph(int threshold) {
  pipeline::BlobGraphOptions o;
  o.threshold = threshold;
  o.source = pipeline::PortType::gray8;
  return pipeline::compile(pipeline::blob_graph(o), pipeline::standard_kernels());
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

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

double time_neopipe(const Frames& f, int threads, double min_seconds) {
  std::int64_t blobs = 0;
  pipeline::ExecutorOptions eo;
  eo.threads = threads;
  pipeline::Executor ex(blob_graph(f.threshold), eo, [&](pipeline::FrameResult&& r) {
    blobs += static_cast<std::int64_t>(std::get<pipeline::BlobList>(r.outputs[0]).size());
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

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

std::vector<BenchRecord> run_blob_bench(const BenchCase& c, const BenchOptions& o) {
  const Frames f = make_frames(c, std::max(o.distinct_frames, 1));
  const auto n = static_cast<int>(f.images.size());
  const auto frame = [&](int i) -> const cv::Mat& { return f.images[static_cast<size_t>(i % n)]; };

  std::vector<double> np;
  std::vector<double> cvv;
  std::vector<double> fl;
  const int saved_cv_threads = cv::getNumThreads();
  cv::setNumThreads(c.threads);
  OpenCvBlobs opencv;
  ReadFloor floor(c.threads);
  // Interleave the implementations so a slow spell of the machine hits all of them alike.
  for (int r = 0; r < std::max(o.repeats, 1); ++r) {
    np.push_back(time_neopipe(f, c.threads, o.min_seconds));
    cvv.push_back(time_loop([&](int i) { opencv(frame(i), f.threshold); }, o.min_seconds));
    fl.push_back(time_loop([&](int i) { floor(frame(i)); }, o.min_seconds));
  }
  cv::setNumThreads(saved_cv_threads);
  const double mpix = c.size.area() / 1e6;
  std::vector<BenchRecord> out;
  for (const auto& [impl, v] : {std::pair{"neopipe", &np}, std::pair{"opencv", &cvv}, std::pair{"floor", &fl}}) {
    const double fps = median(*v);
    out.push_back({c.name, impl, c.size.width, c.size.height, c.threads, fps, fps * mpix});
  }
  return out;
}

std::string cross_check(const BenchCase& c) {
  const Frames f = make_frames(c, 1);
  const auto results = pipeline::run_frames(blob_graph(f.threshold), {f.images.front()}, {});
  const auto ours = std::get<pipeline::BlobList>(results.front().outputs[0]).size();
  OpenCvBlobs opencv;
  const auto theirs = static_cast<size_t>(opencv(f.images.front(), f.threshold));
  if (ours == theirs) return {};
  return c.name + ": neopipe found " + std::to_string(ours) + " blobs, OpenCV " + std::to_string(theirs);
}

}  // namespace neopipe::bench
