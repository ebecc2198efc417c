// Tests of the scheduler (pipeline/executor.hpp). (a) Delay edges: a recursive running average
// (lut2 fed back its own output one frame late, starting from a constant or from the first frame)
// and a frame difference, checked pixel by pixel against sequences computed here by hand. (b)
// Determinism: the built-in blob graph, examples/background_subtraction.yaml, examples/edges.yaml
// and a graph using every standard kernel give bit-identical outputs (images, histograms, blob
// tables) for 1, 2 and 8 threads and 2 or 6 frames in flight. (c) Stripes: with tiny stripes on odd
// heights (37, 17, 3, 2, 1) each node's output equals its kernel applied to the whole frame, and the
// row ranges a node is handed cover every row exactly once. (d) The driver contract: results in
// submission order with their indices, try_submit refusing a frame when the pipeline is full and
// poll delivering without waiting (made deterministic with a test kernel that blocks on a gate the
// test opens), a node's exception naming the node and frame after the earlier results, frames of
// the wrong size or type, an 'image' of the wrong size, output images that stay intact while later
// frames are processed, and destroying an executor with frames still in flight.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "kernels/bool3x3.hpp"
#include "kernels/conv3x3.hpp"
#include "kernels/convert.hpp"
#include "kernels/gray.hpp"
#include "kernels/histogram.hpp"
#include "kernels/lut2.hpp"
#include "kernels/reference/reference.hpp"
#include "kernels/threshold.hpp"
#include "kernels/value_blobs.hpp"
#include "pipeline/builtin_graphs.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/graph_spec.hpp"
#include "pipeline/inline_runner.hpp"
#include "pipeline/kernel_registry.hpp"
#include "pipeline_test_support.hpp"

namespace pl = neopipe::pipeline;
using namespace neopipe::pipeline::testing;  // NOLINT(google-build-using-namespace)
namespace kn = neopipe::kernels;
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------
// Frames

std::vector<cv::Mat> noise_frames(int count, cv::Size size, int type, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f(size, type);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    frames.push_back(f);
  }
  return frames;
}

// A fixed textured background with bright discs moving across it and a little noise per frame:
// something for thresholds, morphology, blobs and background subtraction to work on.
std::vector<cv::Mat> moving_disc_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat background(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      background.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(40 + (x * 50) / size.width),
                                                 static_cast<std::uint8_t>(30 + (y * 40) / size.height), 60);
    }
  }
  struct Disc {
    cv::Point2d p, v;
    int r;
    cv::Scalar colour;
  };
  std::vector<Disc> discs;
  for (int d = 0; d < 7; ++d) {
    discs.push_back({{rng.uniform(0.0, double(size.width)), rng.uniform(0.0, double(size.height))},
                     {rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0)},
                     rng.uniform(3, 12),
                     cv::Scalar(rng.uniform(150, 256), rng.uniform(150, 256), rng.uniform(120, 256))});
  }
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    cv::Mat f = background.clone();
    for (const auto& d : discs) {
      cv::circle(f, cv::Point(int(d.p.x + i * d.v.x) % size.width, int(d.p.y + i * d.v.y + size.height) % size.height),
                 d.r, d.colour, cv::FILLED);
    }
    cv::Mat noise(size, CV_8UC3);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
    f += noise;
    frames.push_back(f);
  }
  return frames;
}

std::vector<cv::Mat> to_gray(const std::vector<cv::Mat>& bgr) {
  std::vector<cv::Mat> out;
  for (const auto& f : bgr) {
    cv::Mat g;
    cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
    out.push_back(g);
  }
  return out;
}

// Frames whose every pixel is their number: test kernels read pixel (0, 0) to know the frame.
std::vector<cv::Mat> numbered_frames(int count, cv::Size size = {8, 6}) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) frames.emplace_back(size, CV_8UC1, cv::Scalar(i));
  return frames;
}

// ---------------------------------------------------------------------------------------------
// Comparisons

// A deep copy of a result's outputs, for checking later that they did not change.
std::vector<pl::Value> deep_copy(const std::vector<pl::Value>& values) {
  std::vector<pl::Value> out;
  for (const auto& v : values) {
    if (const auto* m = std::get_if<cv::Mat>(&v)) {
      out.emplace_back(m->clone());
    } else {
      out.push_back(v);
    }
  }
  return out;
}

const cv::Mat& image_output(const pl::FrameResult& r, size_t k) {
  return std::get<cv::Mat>(r.outputs.at(k));
}

// ---------------------------------------------------------------------------------------------
// Graphs

// Running average out[t] = floor((src[t] + 3 out[t-1]) / 4), out[-1] = `initial`.
std::string running_average_yaml(const std::string& initial) {
  return "nodes:\n"
         "  - {name: src, kernel: source, params: {format: gray}}\n"
         "  - name: avg\n"
         "    kernel: lut2\n"
         "    params: {expr: \"floor((a + 3*b) / 4)\"}\n"
         "    inputs:\n"
         "      a: src\n"
         "      b: {from: avg, delay: 1, initial: " +
         initial +
         "}\n"
         "outputs: avg\n";
}

// Every standard kernel at least once (and a delay), every node an output. `mask_path` is a gray
// image of the frame size for the 'image' kernel.
std::string every_kernel_yaml(const std::string& mask_path) {
  std::string lut_table;
  for (int i = 0; i < 256; ++i) lut_table += (i ? ", " : "") + std::to_string((i * i) / 255);
  std::string bool_table;  // majority of the nine pixels
  for (unsigned i = 0; i < 512; ++i) bool_table += (i ? ", " : "") + std::to_string(__builtin_popcount(i) >= 5 ? 1 : 0);
  return "nodes:\n"
         "  - {name: src, kernel: source, params: {format: bgr}}\n"
         "  - {name: gray, kernel: gray, inputs: {in: src}}\n"
         "  - {name: mask, kernel: image, params: {path: '" +
         mask_path +
         "', format: gray}}\n"
         "  - {name: inv, kernel: lut, params: {expr: 255 - a}, inputs: {in: gray}}\n"
         "  - {name: square, kernel: lut, params: {table: [" +
         lut_table +
         "]}, inputs: {in: gray}}\n"
         "  - {name: otsu, kernel: threshold, params: {value: otsu}, inputs: {in: gray}}\n"
         "  - {name: fixed, kernel: threshold, params: {value: 100, high: 200}, inputs: {in: inv}}\n"
         "  - {name: add, kernel: add, inputs: {a: gray, b: square}}\n"
         "  - {name: sub, kernel: sub, inputs: {a: gray, b: square}}\n"
         "  - {name: absdiff, kernel: absdiff, inputs: {a: gray, b: square}}\n"
         "  - {name: min, kernel: min, inputs: {a: gray, b: inv}}\n"
         "  - {name: max, kernel: max, inputs: {a: gray, b: inv}}\n"
         "  - {name: and, kernel: and, inputs: {a: gray, b: mask}}\n"
         "  - {name: or, kernel: or, inputs: {a: gray, b: fixed}}\n"
         "  - {name: xor, kernel: xor, inputs: {a: gray, b: square}}\n"
         "  - name: mix\n"
         "    kernel: lut2\n"
         "    params: {expr: \"a > b ? a - b : (a + 7*b + 4) / 8\"}\n"
         "    inputs: {a: gray, b: {from: mix, delay: 1, initial: gray}}\n"
         "  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: gray}}\n"
         "  - {name: sharp, kernel: conv3x3, params: {preset: sharpen, border: constant, border_value: 30}, inputs: "
         "{in: smooth}}\n"
         "  - {name: gx, kernel: conv3x3, params: {preset: sobel_x, output: s16}, inputs: {in: gray}}\n"
         "  - {name: lap, kernel: conv3x3, params: {weights: [1, 2, 1, 0, -8, 0, 1, 2, 1], shift: 1, output: s16}, "
         "inputs: {in: smooth}}\n"
         "  - {name: gxm, kernel: convert, params: {abs: true, shift: 2}, inputs: {in: gx}}\n"
         "  - {name: lapc, kernel: convert, params: {abs: false}, inputs: {in: lap}}\n"
         "  - {name: eroded, kernel: bool3x3, params: {op: erode}, inputs: {in: otsu}}\n"
         "  - {name: dilated, kernel: bool3x3, params: {op: dilate, border: constant, border_value: 1}, inputs: {in: "
         "otsu}}\n"
         "  - {name: hitmiss, kernel: bool3x3, params: {pattern: 'x1x 111 x1x', high: 128}, inputs: {in: otsu}}\n"
         "  - {name: outline, kernel: bool3x3, params: {expr: 'c && !(n && s && e && w)'}, inputs: {in: otsu}}\n"
         "  - {name: majority, kernel: bool3x3, params: {table: [" +
         bool_table +
         "]}, inputs: {in: fixed}}\n"
         "  - {name: hist, kernel: histogram, inputs: {in: gray}}\n"
         "  - {name: blobs, kernel: blobs, params: {threshold: 0, connectivity: 4}, inputs: {in: eroded, weights: "
         "gray}}\n"
         "  - {name: blobs_otsu, kernel: blobs, params: {threshold: otsu}, inputs: {in: smooth, weights: mix}}\n"
         "outputs: [gray, mask, inv, square, otsu, fixed, add, sub, absdiff, min, max, and, or, xor, mix, smooth, "
         "sharp,\n"
         "          gx, lap, gxm, lapc, eroded, dilated, hitmiss, outline, majority, hist, blobs, blobs_otsu]\n";
}

// ---------------------------------------------------------------------------------------------
// Test kernels: deterministic blocking and failing, driven by the frame number in pixel (0, 0)

// A gate a test kernel waits at until the test opens it; the test can wait until a kernel arrives.
class Gate {
 public:
  void arrive_and_wait() {
    std::unique_lock lk(m_);
    arrived_ = true;
    cv_.notify_all();
    cv_.wait(lk, [&] { return open_; });
  }
  void wait_for_arrival() {
    std::unique_lock lk(m_);
    cv_.wait(lk, [&] { return arrived_; });
  }
  void open() {
    std::lock_guard lk(m_);
    open_ = true;
    cv_.notify_all();
  }
  // Fails frame `frame` once the kernel held at the gate has arrived, releasing it: the failure is
  // on its way while the held frame is still in flight.
  [[noreturn]] void fail_once_arrived(int frame) {
    wait_for_arrival();
    open();
    throw std::runtime_error("failure at frame " + std::to_string(frame));
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool arrived_ = false;
  bool open_ = false;
};

// Copies its gray input; on the frame numbered `block_at` waits at the gate (param block_at), on
// the frame numbered `throw_at` throws (param throw_at). A whole-frame node, so it runs in one go.
class TestNode final : public pl::Node {
 public:
  TestNode(std::shared_ptr<Gate> gate, int block_at, int throw_at)
      : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, kn::Footprint::frame),
        gate_(std::move(gate)),
        block_at_(block_at),
        throw_at_(throw_at) {}
  void begin_frame(pl::NodeIO& io) override {
    const int frame = io.image(0).at<std::uint8_t>(0, 0);
    if (frame == block_at_) gate_->arrive_and_wait();
    if (frame == throw_at_) throw std::runtime_error("test failure at frame " + std::to_string(frame));
    io.image(0).copyTo(io.out_image(0));
  }

 private:
  std::shared_ptr<Gate> gate_;
  int block_at_;
  int throw_at_;
};

pl::KernelRegistry registry_with_test_node(std::shared_ptr<Gate> gate) {
  pl::KernelRegistry r = pl::standard_kernels();
  r.add({"test", "copies its input; blocks at frame block_at, throws at frame throw_at", [gate](pl::NodeContext& c) {
           const int block_at = c.params.get_int("block_at", -1, -1, 255);
           const int throw_at = c.params.get_int("throw_at", -1, -1, 255);
           return std::make_unique<TestNode>(gate, block_at, throw_at);
         }});
  return r;
}

// source (gray) -> t (test kernel with `params`) [-> after (lut 255 - a)]; outputs t [and after].
pl::CompiledGraph test_node_graph(std::shared_ptr<Gate> gate, const std::string& params, bool with_after = false) {
  std::string yaml =
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - {name: t, kernel: test, params: " +
      params + ", inputs: {in: src}}\n";
  if (with_after) yaml += "  - {name: after, kernel: lut, params: {expr: 255 - a}, inputs: {in: t}}\n";
  yaml += with_after ? "outputs: [t, after]\n" : "outputs: t\n";
  return compile_yaml(yaml, registry_with_test_node(std::move(gate)));
}

// Runs `make_graph()` on `frames` with each option set and requires every output of every frame
// to equal the single-threaded, two-frames-in-flight run. Returns that reference run.
std::vector<pl::FrameResult> expect_deterministic(const std::function<pl::CompiledGraph()>& make_graph,
                                                  const std::vector<cv::Mat>& frames) {
  const pl::ExecutorOptions reference_options{.threads = 1, .frames_in_flight = 2};
  const auto reference = pl::run_frames(make_graph(), frames, reference_options);
  EXPECT_EQ(reference.size(), frames.size());
  const pl::ExecutorOptions variants[] = {
      {.threads = 1, .frames_in_flight = 6}, {.threads = 2, .frames_in_flight = 2},
      {.threads = 2, .frames_in_flight = 6}, {.threads = 8, .frames_in_flight = 2},
      {.threads = 8, .frames_in_flight = 6}, {.threads = 8, .frames_in_flight = 6, .min_stripe_rows = 3},
  };
  for (const auto& o : variants) {
    const std::string config = "threads " + std::to_string(o.threads) + ", frames in flight " +
                               std::to_string(o.frames_in_flight) + ", min stripe rows " +
                               std::to_string(o.min_stripe_rows);
    SCOPED_TRACE(config);
    const auto results = pl::run_frames(make_graph(), frames, o);
    EXPECT_EQ(results.size(), reference.size());
    for (size_t f = 0; f < std::min(results.size(), reference.size()); ++f) {
      EXPECT_EQ(results[f].index, static_cast<std::int64_t>(f));
      EXPECT_EQ(results[f].outputs.size(), reference[f].outputs.size());
      for (size_t k = 0; k < std::min(results[f].outputs.size(), reference[f].outputs.size()); ++k) {
        expect_same_value(results[f].outputs[k], reference[f].outputs[k],
                          "frame " + std::to_string(f) + ", output " + std::to_string(k));
      }
    }
  }
  // The same frames one at a time on the calling thread, as a navigator's eye runs them.
  pl::InlineRunner runner(make_graph());
  for (size_t f = 0; f < std::min(frames.size(), reference.size()); ++f) {
    const std::vector<pl::Value>& outputs = runner.run(frames[f]);
    EXPECT_EQ(outputs.size(), reference[f].outputs.size());
    for (size_t k = 0; k < std::min(outputs.size(), reference[f].outputs.size()); ++k) {
      expect_same_value(outputs[k], reference[f].outputs[k],
                        "inline, frame " + std::to_string(f) + ", output " + std::to_string(k));
    }
  }
  EXPECT_EQ(runner.frames(), static_cast<std::int64_t>(frames.size()));
  return reference;
}

size_t total_blobs(const std::vector<pl::FrameResult>& results, size_t output) {
  size_t n = 0;
  for (const auto& r : results) n += std::get<pl::BlobList>(r.outputs.at(output)).size();
  return n;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// (a) Delay semantics

TEST(ExecutorDelay, RunningAverageFromAConstant) {
  const auto frames = noise_frames(10, {23, 17}, CV_8UC1, 7);
  for (int initial : {0, 200}) {
    SCOPED_TRACE("initial " + std::to_string(initial));
    // By hand: out[t] = floor((src[t] + 3 out[t-1]) / 4), out[-1] = initial.
    std::vector<cv::Mat> expected;
    cv::Mat prev(frames[0].size(), CV_8UC1, cv::Scalar(initial));
    for (const auto& f : frames) {
      cv::Mat out(f.size(), CV_8UC1);
      for (int y = 0; y < f.rows; ++y) {
        for (int x = 0; x < f.cols; ++x) {
          out.at<std::uint8_t>(y, x) =
              static_cast<std::uint8_t>((f.at<std::uint8_t>(y, x) + 3 * prev.at<std::uint8_t>(y, x)) / 4);
        }
      }
      expected.push_back(out);
      prev = out;
    }
    for (const pl::ExecutorOptions o :
         {pl::ExecutorOptions{.threads = 1, .frames_in_flight = 2},
          pl::ExecutorOptions{.threads = 4, .frames_in_flight = 6, .min_stripe_rows = 2}}) {
      const auto results = pl::run_frames(compile_yaml(running_average_yaml(std::to_string(initial))), frames, o);
      ASSERT_EQ(results.size(), frames.size());
      for (size_t t = 0; t < frames.size(); ++t) {
        EXPECT_TRUE(same_image(image_output(results[t], 0), expected[t])) << "frame " << t;
      }
    }
  }
}

TEST(ExecutorDelay, RunningAverageFromTheFirstFrame) {
  const auto frames = noise_frames(10, {23, 17}, CV_8UC1, 8);
  // out[-1] = src[0], so out[0] = floor((src[0] + 3 src[0]) / 4) = src[0].
  std::vector<cv::Mat> expected;
  cv::Mat prev = frames[0];
  for (const auto& f : frames) {
    cv::Mat out(f.size(), CV_8UC1);
    for (int y = 0; y < f.rows; ++y) {
      for (int x = 0; x < f.cols; ++x) {
        out.at<std::uint8_t>(y, x) =
            static_cast<std::uint8_t>((f.at<std::uint8_t>(y, x) + 3 * prev.at<std::uint8_t>(y, x)) / 4);
      }
    }
    expected.push_back(out);
    prev = out;
  }
  EXPECT_TRUE(same_image(expected[0], frames[0]));
  for (int threads : {1, 3}) {
    const auto results = pl::run_frames(compile_yaml(running_average_yaml("src")), frames,
                                        {.threads = threads, .frames_in_flight = 4, .min_stripe_rows = 1});
    ASSERT_EQ(results.size(), frames.size());
    for (size_t t = 0; t < frames.size(); ++t) {
      EXPECT_TRUE(same_image(image_output(results[t], 0), expected[t])) << "threads " << threads << ", frame " << t;
    }
  }
}

TEST(ExecutorDelay, FrameDifference) {
  const auto frames = noise_frames(8, {19, 11}, CV_8UC1, 9);
  const std::string yaml =
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - {name: diff, kernel: absdiff, inputs: {a: src, b: {from: src, delay: 1, initial: 50}}}\n"
      "  - {name: still, kernel: absdiff, inputs: {a: src, b: {from: src, delay: 1, initial: src}}}\n"
      "outputs: [diff, still]\n";
  const auto results = pl::run_frames(compile_yaml(yaml), frames, {.threads = 2, .frames_in_flight = 3});
  ASSERT_EQ(results.size(), frames.size());
  for (size_t t = 0; t < frames.size(); ++t) {
    cv::Mat previous = t == 0 ? cv::Mat(frames[0].size(), CV_8UC1, cv::Scalar(50)) : frames[t - 1];
    cv::Mat expected(frames[t].size(), CV_8UC1);
    for (int y = 0; y < expected.rows; ++y) {
      for (int x = 0; x < expected.cols; ++x) {
        expected.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(
            std::abs(int{frames[t].at<std::uint8_t>(y, x)} - int{previous.at<std::uint8_t>(y, x)}));
      }
    }
    EXPECT_TRUE(same_image(image_output(results[t], 0), expected)) << "frame " << t;
    if (t == 0) {
      EXPECT_EQ(cv::countNonZero(image_output(results[t], 1)), 0);  // the first frame against itself
    } else {
      EXPECT_TRUE(same_image(image_output(results[t], 1), expected)) << "frame " << t;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// (b) Determinism across thread counts and frames in flight

TEST(ExecutorDeterminism, BuiltInBlobGraph) {
  const auto frames = moving_disc_frames(32, {128, 96}, 101);
  const auto reference =
      expect_deterministic([] { return pl::compile(pl::blob_graph(), pl::standard_kernels()); }, frames);
  EXPECT_GT(total_blobs(reference, 0), frames.size());  // there is something to agree on
}

TEST(ExecutorDeterminism, BackgroundSubtractionExample) {
  const auto frames = moving_disc_frames(32, {128, 96}, 102);
  const auto reference = expect_deterministic([] { return compile_example("background_subtraction.yaml"); }, frames);
  EXPECT_GT(total_blobs(reference, 0), 10U);
}

TEST(ExecutorDeterminism, EdgesExample) {
  const auto frames = to_gray(moving_disc_frames(32, {128, 96}, 103));
  const auto reference = expect_deterministic([] { return compile_example("edges.yaml"); }, frames);
  EXPECT_GT(total_blobs(reference, 0), 10U);
}

TEST(ExecutorDeterminism, EveryStandardKernel) {
  const TempDir dir("neopipe_executor_every_kernel");
  const cv::Size size(96, 70);
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  cv::circle(mask, {48, 35}, 30, cv::Scalar(255), cv::FILLED);
  const std::string mask_path = (dir.path() / "mask.png").string();
  ASSERT_TRUE(cv::imwrite(mask_path, mask));
  const std::string yaml = every_kernel_yaml(mask_path);
  const auto frames = moving_disc_frames(32, size, 104);
  const auto reference = expect_deterministic([&] { return compile_yaml(yaml); }, frames);
  ASSERT_EQ(reference.at(0).outputs.size(), 29U);
  EXPECT_GT(total_blobs(reference, 27), 0U);
  EXPECT_GT(total_blobs(reference, 28), 0U);
  // Spot checks that the graph computes what it says, so agreeing is not trivially true.
  cv::Mat gray;
  cv::cvtColor(frames[5], gray, cv::COLOR_BGR2GRAY);
  EXPECT_TRUE(same_image(image_output(reference[5], 0), gray));
  EXPECT_TRUE(same_image(image_output(reference[5], 1), mask));
  EXPECT_TRUE(same_image(image_output(reference[5], 2), 255 - gray));
  EXPECT_TRUE(std::get<pl::Histogram>(reference[5].outputs[26]) == kn::histogram(gray));
}

// ---------------------------------------------------------------------------------------------
// (c) Stripes: many small stripes give exactly the whole-frame kernels

TEST(ExecutorStripes, NodesEqualTheirKernelsOnTheWholeFrame) {
  const std::string yaml =
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: bgr}}\n"
      "  - {name: gray, kernel: gray, inputs: {in: src}}\n"
      "  - {name: smooth, kernel: conv3x3, params: {preset: smooth, border: constant, border_value: 9}, inputs: {in: "
      "gray}}\n"
      "  - {name: gx, kernel: conv3x3, params: {preset: sobel_x, output: s16}, inputs: {in: gray}}\n"
      "  - {name: gxm, kernel: convert, params: {abs: true, shift: 1}, inputs: {in: gx}}\n"
      "  - {name: bin, kernel: threshold, params: {value: otsu}, inputs: {in: smooth}}\n"
      "  - {name: eroded, kernel: bool3x3, params: {op: erode}, inputs: {in: bin}}\n"
      "  - {name: mix, kernel: lut2, params: {expr: 'a > b ? a - b : 0'}, inputs: {a: gray, b: smooth}}\n"
      "outputs: [gray, smooth, gx, gxm, bin, eroded, mix]\n";
  kn::Conv3x3 smooth = kn::smooth3x3();
  smooth.border = {kn::BorderMode::constant, 9};
  kn::Bool3x3 erode;
  erode.table = kn::erode_table();
  const kn::Lut2 mix =
      kn::Lut2::from_function([](int a, int b) { return static_cast<std::uint8_t>(a > b ? a - b : 0); });
  const kn::ConvertS16 convert{true, 1};

  for (const cv::Size size :
       {cv::Size(31, 37), cv::Size(33, 17), cv::Size(45, 1), cv::Size(1, 37), cv::Size(7, 2), cv::Size(64, 3)}) {
    for (int min_rows : {1, 2}) {
      SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height) + ", min_stripe_rows " +
                   std::to_string(min_rows));
      const auto frames = noise_frames(3, size, CV_8UC3, 300 + size.area());
      const auto results = pl::run_frames(compile_yaml(yaml), frames,
                                          {.threads = 8, .frames_in_flight = 2, .min_stripe_rows = min_rows});
      ASSERT_EQ(results.size(), frames.size());
      for (size_t f = 0; f < frames.size(); ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        cv::Mat gray, smoothed, gx, gxm, bin, eroded, mixed;
        kn::bgr_to_gray(frames[f], gray);
        kn::conv3x3(gray, smoothed, smooth, CV_8UC1);
        kn::conv3x3(gray, gx, kn::sobel_x3x3(), CV_16SC1);
        kn::convert_s16(gx, gxm, convert);
        kn::threshold(smoothed, bin, kn::otsu_threshold(kn::histogram(smoothed)));
        kn::bool3x3(bin, eroded, erode);
        kn::lut2(gray, smoothed, mixed, mix);
        // The whole-frame kernels agree with the scalar references and OpenCV, so stripes are
        // compared against an independent result.
        cv::Mat cv_gray;
        cv::cvtColor(frames[f], cv_gray, cv::COLOR_BGR2GRAY);
        ASSERT_TRUE(same_image(gray, cv_gray));
        ASSERT_TRUE(same_image(smoothed, kn::reference::conv3x3(gray, smooth, CV_8UC1)));
        ASSERT_TRUE(same_image(gx, kn::reference::conv3x3(gray, kn::sobel_x3x3(), CV_16SC1)));

        const cv::Mat* expected[] = {&gray, &smoothed, &gx, &gxm, &bin, &eroded, &mixed};
        for (size_t k = 0; k < 7; ++k) {
          EXPECT_TRUE(same_image(image_output(results[f], k), *expected[k])) << "output " << k;
        }
      }
    }
  }
}

namespace {

// A point node that copies its input and records every row range the scheduler hands it.
class RowRecorder final : public pl::Node {
 public:
  explicit RowRecorder(std::shared_ptr<std::vector<cv::Range>> calls)
      : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, kn::Footprint::point),
        calls_(std::move(calls)) {}
  void run_rows(pl::NodeIO& io, cv::Range rows) const override {
    {
      std::lock_guard lk(m_);
      calls_->push_back(rows);
    }
    const cv::Mat& in = io.image(0);
    cv::Mat& out = io.out_image(0);
    for (int y = std::max(rows.start, 0); y < std::min(rows.end, in.rows); ++y) in.row(y).copyTo(out.row(y));
  }

 private:
  std::shared_ptr<std::vector<cv::Range>> calls_;
  mutable std::mutex m_;
};

// Runs one frame of `size` through source -> RowRecorder with the given stripe options; returns
// the row ranges of that frame.
std::vector<cv::Range> recorded_stripes(cv::Size size, int threads, int min_rows) {
  auto calls = std::make_shared<std::vector<cv::Range>>();
  pl::KernelRegistry r = pl::standard_kernels();
  r.add({"record", "copies; records its row ranges",
         [calls](pl::NodeContext&) { return std::make_unique<RowRecorder>(calls); }});
  const auto frames = noise_frames(1, size, CV_8UC1, 900);
  const auto results = pl::run_frames(compile_yaml("nodes:\n"
                                                   "  - {name: src, kernel: source, params: {format: gray}}\n"
                                                   "  - {name: rec, kernel: record, inputs: {in: src}}\n"
                                                   "outputs: rec\n",
                                                   r),
                                      frames, {.threads = threads, .frames_in_flight = 2, .min_stripe_rows = min_rows});
  EXPECT_EQ(results.size(), 1U);
  if (!results.empty()) {
    EXPECT_TRUE(same_image(image_output(results[0], 0), frames[0]));
  }
  return *calls;
}

}  // namespace

TEST(ExecutorStripes, StripesCoverEveryRowOnce) {
  struct Case {
    cv::Size size;
    int threads, min_rows;
    size_t min_stripes;  // at least this many non-empty stripes
  };
  const Case cases[] = {{{9, 37}, 8, 1, 8}, {{9, 37}, 8, 2, 8}, {{5, 100}, 3, 16, 6},
                        {{5, 1}, 8, 1, 1},  {{5, 37}, 1, 1, 1}, {{5, 15}, 4, 16, 1}};
  for (const auto& c : cases) {
    SCOPED_TRACE(std::to_string(c.size.height) + " rows, " + std::to_string(c.threads) + " threads, min " +
                 std::to_string(c.min_rows));
    const auto calls = recorded_stripes(c.size, c.threads, c.min_rows);
    std::vector<int> covered(static_cast<size_t>(c.size.height), 0);
    size_t non_empty = 0;
    for (const auto& r : calls) {
      const int start = std::max(r.start, 0);
      const int end = std::min(r.end, c.size.height);
      if (start < end) ++non_empty;
      for (int y = start; y < end; ++y) ++covered[static_cast<size_t>(y)];
    }
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), c.size.height) << "every row exactly once";
    EXPECT_GE(non_empty, c.min_stripes);
  }
}

// Every range handed to run_rows lies within the frame, so a node may take its rows with
// Mat::rowRange (regression: 37 rows, 8 threads and min_stripe_rows 1 once gave 32 stripes of 2
// rows, stripes 19..31 being Range(38, 37) ... Range(62, 37), which rowRange rejects).
TEST(ExecutorStripes, EveryStripeLiesWithinTheFrame) {
  for (const int height : {37, 17, 100}) {
    for (const int threads : {3, 8}) {
      const auto calls = recorded_stripes({4, height}, threads, 1);
      for (const auto& r : calls) {
        EXPECT_TRUE(0 <= r.start && r.start <= r.end && r.end <= height)
            << height << " rows, " << threads << " threads: stripe [" << r.start << ", " << r.end << ")";
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// (d) The driver's contract

TEST(Executor, ResultsInSubmissionOrderWithTheirIndices) {
  const auto frames = noise_frames(40, {24, 20}, CV_8UC1, 400);
  std::vector<pl::FrameResult> results;
  {
    pl::Executor ex(compile_yaml("nodes:\n"
                                 "  - {name: src, kernel: source, params: {format: gray}}\n"
                                 "  - {name: inv, kernel: lut, params: {expr: 255 - a}, inputs: {in: src}}\n"
                                 "  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: inv}}\n"
                                 "  - {name: hist, kernel: histogram, inputs: {in: smooth}}\n"
                                 "outputs: [smooth, hist]\n"),
                    {.threads = 8, .frames_in_flight = 6, .min_stripe_rows = 1},
                    [&](pl::FrameResult&& r) { results.push_back(std::move(r)); });
    EXPECT_EQ(ex.threads(), 8);
    EXPECT_EQ(ex.frames_in_flight(), 6);
    for (size_t i = 0; i < frames.size(); ++i) ex.submit(1000 - 7 * static_cast<std::int64_t>(i), frames[i]);
    ex.finish();
    ex.finish();  // nothing left: returns at once
  }
  ASSERT_EQ(results.size(), frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    EXPECT_EQ(results[i].index, 1000 - 7 * static_cast<std::int64_t>(i));
    EXPECT_EQ(results[i].input.data, frames[i].data);  // the frame as submitted
    EXPECT_GE(results[i].latency_s, 0);
    cv::Mat expected;
    kn::conv3x3(255 - frames[i], expected, kn::smooth3x3());
    EXPECT_TRUE(same_image(image_output(results[i], 0), expected));
    EXPECT_TRUE(std::get<pl::Histogram>(results[i].outputs[1]) == kn::histogram(expected));
  }
}

TEST(Executor, OptionDefaults) {
  const auto graph = [] { return pl::compile(pl::blob_graph(), pl::standard_kernels()); };
  pl::Executor defaults(graph(), {}, [](pl::FrameResult&&) {});
  EXPECT_GE(defaults.threads(), 1);
  EXPECT_EQ(defaults.frames_in_flight(), 2 * (defaults.threads() + 2));
  pl::Executor one(graph(), {.threads = 3, .frames_in_flight = 1}, [](pl::FrameResult&&) {});
  EXPECT_EQ(one.threads(), 3);
  EXPECT_EQ(one.frames_in_flight(), 2);       // at least two
  EXPECT_EQ(one.graph().nodes().size(), 3U);  // src, gray, blobs (the threshold folded into blobs)
}

TEST(Executor, RunFramesNumbersFromZero) {
  const auto results = pl::run_frames(
      pl::compile(pl::blob_graph({.threshold = std::nullopt, .connectivity = 8, .source = pl::PortType::gray8}),
                  pl::standard_kernels()),
      noise_frames(5, {16, 16}, CV_8UC1, 5), {.threads = 2});
  ASSERT_EQ(results.size(), 5U);
  for (size_t i = 0; i < results.size(); ++i) EXPECT_EQ(results[i].index, static_cast<std::int64_t>(i));
}

TEST(Executor, TrySubmitRefusesAFrameWhenThePipelineIsFull) {
  auto gate = std::make_shared<Gate>();
  std::vector<std::int64_t> delivered;
  const auto frames = numbered_frames(4);
  pl::Executor ex(test_node_graph(gate, "{block_at: 0}"), {.threads = 2, .frames_in_flight = 2},
                  [&](pl::FrameResult&& r) { delivered.push_back(r.index); });
  EXPECT_TRUE(ex.try_submit(10, frames[0]));  // blocks in the test node until the gate opens
  EXPECT_TRUE(ex.try_submit(11, frames[1]));  // the second slot
  gate->wait_for_arrival();
  EXPECT_FALSE(ex.try_submit(12, frames[2]));  // full: frame 0 cannot finish
  EXPECT_FALSE(ex.try_submit(12, frames[2]));
  ex.poll();
  EXPECT_TRUE(delivered.empty());
  gate->open();
  ex.finish();
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{10, 11}));
  EXPECT_TRUE(ex.try_submit(12, frames[2]));  // room again
  ex.submit(13, frames[3]);
  ex.finish();
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{10, 11, 12, 13}));
}

TEST(Executor, PollDeliversFinishedResultsWithoutWaiting) {
  auto gate = std::make_shared<Gate>();
  std::vector<std::int64_t> delivered;
  const auto frames = numbered_frames(3);
  pl::Executor ex(test_node_graph(gate, "{block_at: 1}"), {.threads = 2, .frames_in_flight = 4},
                  [&](pl::FrameResult&& r) { delivered.push_back(r.index); });
  ex.submit(0, frames[0]);
  ex.submit(1, frames[1]);
  // The test node starts frame 1 only after finishing frame 0, the graph's last node: frame 0 is
  // complete once frame 1 waits at the gate.
  gate->wait_for_arrival();
  ex.poll();
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0}));
  ex.submit(2, frames[2]);  // there is room; frame 2 waits behind frame 1
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0}));
  gate->open();
  ex.finish();
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1, 2}));
}

TEST(Executor, NodeErrorNamesNodeAndFrameAfterEarlierResults) {
  auto gate = std::make_shared<Gate>();
  std::vector<std::int64_t> delivered;
  std::string error;
  const auto frames = numbered_frames(10);
  {
    pl::Executor ex(test_node_graph(gate, "{throw_at: 5}"), {.threads = 4, .frames_in_flight = 4},
                    [&](pl::FrameResult&& r) { delivered.push_back(r.index); });
    try {
      for (int i = 0; i < 10; ++i) ex.submit(100 + i, frames[static_cast<size_t>(i)]);
      ex.finish();
      ADD_FAILURE() << "no error surfaced";
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
    // The executor stays failed: later calls report the same error.
    try {
      ex.finish();
      ADD_FAILURE() << "finish() after the error succeeded";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), error);
    }
  }
  EXPECT_EQ(error, "frame 105, node 't' (test): test failure at frame 5");
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{100, 101, 102, 103, 104}));
}

// When a node fails on frame 5, frames before it that still have nodes to run are finished and
// delivered: here frame 4's last node is held back until the failure at frame 5 is on its way.
// (Regression: the executor once stopped spawning every task after the first error, losing frame 4
// and often 2 and 3.) The outcome must not depend on the interleaving.
TEST(Executor, NodeErrorStillDeliversEveryEarlierFrame) {
  struct Hold final : pl::Node {
    explicit Hold(std::shared_ptr<Gate> g)
        : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, kn::Footprint::frame),
          gate(std::move(g)) {}
    void begin_frame(pl::NodeIO& io) override {
      if (io.image(0).at<std::uint8_t>(0, 0) == 4) gate->arrive_and_wait();
      io.image(0).copyTo(io.out_image(0));
    }
    std::shared_ptr<Gate> gate;
  };
  struct Fail final : pl::Node {
    explicit Fail(std::shared_ptr<Gate> g)
        : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, kn::Footprint::frame),
          gate(std::move(g)) {}
    void begin_frame(pl::NodeIO& io) override {
      if (io.image(0).at<std::uint8_t>(0, 0) == 5) gate->fail_once_arrived(5);
      io.image(0).copyTo(io.out_image(0));
    }
    std::shared_ptr<Gate> gate;
  };
  auto gate = std::make_shared<Gate>();
  pl::KernelRegistry r = pl::standard_kernels();
  r.add({"hold", "", [gate](pl::NodeContext&) { return std::make_unique<Hold>(gate); }});
  r.add({"fail", "", [gate](pl::NodeContext&) { return std::make_unique<Fail>(gate); }});
  pl::CompiledGraph g = compile_yaml(
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - {name: fail, kernel: fail, inputs: {in: src}}\n"
      "  - {name: hold, kernel: hold, inputs: {in: src}}\n"
      "  - {name: after, kernel: lut, params: {expr: a}, inputs: {in: hold}}\n"
      "outputs: [fail, after]\n",
      r);
  std::vector<std::int64_t> delivered;
  const auto frames = numbered_frames(8);
  {
    pl::Executor ex(std::move(g), {.threads = 3, .frames_in_flight = 8},
                    [&](pl::FrameResult&& res) { delivered.push_back(res.index); });
    EXPECT_THROW(
        {
          for (int i = 0; i < 8; ++i) ex.submit(i, frames[static_cast<size_t>(i)]);
          ex.finish();
        },
        std::runtime_error);
  }
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
}

// Two frames fail, the later one first: the error reported is the earlier frame's, the one a
// sequential run would have hit (tests/mutation/mutants.json, P06). Frame 3 waits until frame 5 has
// reached the node, so both are in flight; with the real executor the outcome does not depend on
// which error is recorded first.
TEST(Executor, TheEarliestFramesErrorWinsWhateverTheOrderOfFailures) {
  struct FailTwice final : pl::Node {
    explicit FailTwice(std::shared_ptr<Gate> g)
        : Node({{"in", pl::PortType::gray8}}, {{"out", pl::PortType::gray8}}, kn::Footprint::frame,
               pl::FrameOrder::any),
          gate(std::move(g)) {}
    void begin_frame(pl::NodeIO& io) override {
      const int frame = io.image(0).at<std::uint8_t>(0, 0);
      if (frame == 3) {
        gate->arrive_and_wait();
        // Lets frame 5's error be recorded first (in the usual interleaving; either is correct).
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        throw std::runtime_error("failure at frame 3");
      }
      if (frame == 5) gate->fail_once_arrived(5);
      io.image(0).copyTo(io.out_image(0));
    }
    std::shared_ptr<Gate> gate;
  };
  auto gate = std::make_shared<Gate>();
  pl::KernelRegistry r = pl::standard_kernels();
  r.add({"fail_twice", "", [gate](pl::NodeContext&) { return std::make_unique<FailTwice>(gate); }});
  pl::CompiledGraph g = compile_yaml(
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - {name: f, kernel: fail_twice, inputs: {in: src}}\n"
      "outputs: f\n",
      r);
  std::vector<std::int64_t> delivered;
  std::string error;
  const auto frames = numbered_frames(8);
  {
    pl::Executor ex(std::move(g), {.threads = 3, .frames_in_flight = 8},
                    [&](pl::FrameResult&& res) { delivered.push_back(res.index); });
    try {
      for (int i = 0; i < 8; ++i) ex.submit(i, frames[static_cast<size_t>(i)]);
      ex.finish();
      ADD_FAILURE() << "no error surfaced";
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
  }
  EXPECT_EQ(error, "frame 3, node 'f' (fail_twice): failure at frame 3");
  EXPECT_EQ(delivered, (std::vector<std::int64_t>{0, 1, 2}));
}

TEST(Executor, DestroyedWithFramesInFlight) {
  auto gate = std::make_shared<Gate>();
  std::vector<std::int64_t> delivered;
  const auto frames = numbered_frames(6);
  {
    pl::Executor ex(test_node_graph(gate, "{block_at: 2}", true), {.threads = 2, .frames_in_flight = 6},
                    [&](pl::FrameResult&& r) { delivered.push_back(r.index); });
    for (int i = 0; i < 6; ++i) ex.submit(i, frames[static_cast<size_t>(i)]);
    gate->wait_for_arrival();
    gate->open();  // the destructor waits for running tasks; frames not finished are never delivered
  }
  ASSERT_LE(delivered.size(), 6U);
  for (size_t i = 0; i < delivered.size(); ++i) EXPECT_EQ(delivered[i], static_cast<std::int64_t>(i));
}

TEST(Executor, FramesOfTheWrongTypeOrSize) {
  std::vector<pl::FrameResult> results;
  pl::Executor ex(pl::compile(pl::blob_graph(), pl::standard_kernels()), {.threads = 2},
                  [&](pl::FrameResult&& r) { results.push_back(std::move(r)); });
  const cv::Mat gray(24, 32, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(ex.submit(0, gray), std::invalid_argument);                                // bgr8 graph
  EXPECT_THROW(ex.submit(0, cv::Mat()), std::invalid_argument);                           // empty
  EXPECT_THROW(ex.submit(0, cv::Mat(24, 32, CV_16UC3)), std::invalid_argument);           // 16 bits
  EXPECT_THROW((void)ex.try_submit(0, cv::Mat(24, 32, CV_8UC4)), std::invalid_argument);  // four channels
  const auto frames = moving_disc_frames(3, {32, 24}, 600);
  ex.submit(0, frames[0]);  // the stream's size is now 32x24
  try {
    ex.submit(1, cv::Mat(25, 32, CV_8UC3, cv::Scalar(0)));
    ADD_FAILURE() << "a frame of another size was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "frame 1 is 32x25 but the stream started at 32x24");
  }
  EXPECT_THROW(ex.submit(1, cv::Mat(24, 33, CV_8UC3, cv::Scalar(0))), std::invalid_argument);
  // The refused frames left no trace: the stream goes on.
  ex.submit(1, frames[1]);
  ex.submit(2, frames[2]);
  ex.finish();
  ASSERT_EQ(results.size(), 3U);
  const auto expected = pl::run_frames(pl::compile(pl::blob_graph(), pl::standard_kernels()), frames);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(results[i].index, static_cast<std::int64_t>(i));
    expect_same_value(results[i].outputs[0], expected[i].outputs[0], "frame " + std::to_string(i));
  }
}

TEST(Executor, ImageOfTheWrongSizeFailsAtTheFirstFrame) {
  const TempDir dir("neopipe_executor_image_size");
  const std::string mask_path = (dir.path() / "mask.png").string();
  ASSERT_TRUE(cv::imwrite(mask_path, cv::Mat(10, 10, CV_8UC1, cv::Scalar(255))));
  const std::string yaml =
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - name: mask\n"
      "    kernel: image\n"
      "    params: {path: '" +
      mask_path +
      "'}\n"
      "  - {name: masked, kernel: and, inputs: {a: src, b: mask}}\n"
      "outputs: masked\n";
  pl::Executor ex(compile_yaml(yaml), {.threads = 2}, [](pl::FrameResult&&) {});
  try {
    ex.submit(0, cv::Mat(10, 12, CV_8UC1, cv::Scalar(1)));
    ADD_FAILURE() << "a 12x10 frame was taken with a 10x10 image";
  } catch (const pl::GraphError& e) {
    EXPECT_EQ(std::string(e.what()),
              "spec.yaml:3:5: node 'mask': size mismatch: image '" + mask_path + "' is 10x10 but the frames are 12x10");
    EXPECT_EQ(e.where().line, 3);
  }
  // The same graph runs at the image's size.
  const auto results = pl::run_frames(compile_yaml(yaml), {cv::Mat(10, 10, CV_8UC1, cv::Scalar(77))});
  ASSERT_EQ(results.size(), 1U);
  EXPECT_TRUE(same_image(image_output(results[0], 0), cv::Mat(10, 10, CV_8UC1, cv::Scalar(77))));
}

TEST(Executor, OutputImagesStayValidAfterLaterFrames) {
  const std::string yaml =
      "nodes:\n"
      "  - {name: src, kernel: source, params: {format: gray}}\n"
      "  - {name: inv, kernel: lut, params: {expr: 255 - a}, inputs: {in: src}}\n"
      "  - {name: smooth, kernel: conv3x3, params: {preset: smooth}, inputs: {in: inv}}\n"
      "  - name: avg\n"
      "    kernel: lut2\n"
      "    params: {expr: \"floor((a + 3*b) / 4)\"}\n"
      "    inputs: {a: smooth, b: {from: avg, delay: 1, initial: 0}}\n"
      "  - {name: gx, kernel: conv3x3, params: {preset: sobel_x, output: s16}, inputs: {in: avg}}\n"
      "  - {name: hist, kernel: histogram, inputs: {in: smooth}}\n"
      "  - {name: blobs, kernel: blobs, params: {threshold: 128}, inputs: {in: smooth}}\n"
      "outputs: [inv, smooth, avg, gx, hist, blobs, src]\n";
  const auto frames = noise_frames(24, {40, 30}, CV_8UC1, 700);
  for (const int in_flight : {2, 5}) {
    SCOPED_TRACE("frames in flight " + std::to_string(in_flight));
    std::vector<pl::FrameResult> results;
    pl::Executor ex(compile_yaml(yaml), {.threads = 4, .frames_in_flight = in_flight, .min_stripe_rows = 4},
                    [&](pl::FrameResult&& r) { results.push_back(std::move(r)); });
    ex.submit(0, frames[0]);
    ex.submit(1, frames[1]);
    ex.finish();
    ASSERT_EQ(results.size(), 2U);
    const std::vector<pl::Value> first = deep_copy(results[0].outputs);
    const std::vector<pl::Value> second = deep_copy(results[1].outputs);
    for (size_t i = 2; i < frames.size(); ++i) ex.submit(static_cast<std::int64_t>(i), frames[i]);
    ex.finish();
    ASSERT_EQ(results.size(), frames.size());
    for (size_t k = 0; k < first.size(); ++k) {
      expect_same_value(results[0].outputs[k], first[k], "frame 0, output " + std::to_string(k));
      expect_same_value(results[1].outputs[k], second[k], "frame 1, output " + std::to_string(k));
    }
    // Every frame's images are its own.
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_NE(image_output(results[0], k).data, image_output(results[static_cast<size_t>(in_flight)], k).data)
          << "output " << k;
    }
  }
}

TEST(InlineRunner, RefusesFramesOfTheWrongTypeOrSize) {
  pl::InlineRunner runner(pl::compile(pl::blob_graph(), pl::standard_kernels()));
  EXPECT_THROW(runner.run(cv::Mat(8, 8, CV_8UC1)), std::invalid_argument);  // the built-in graph takes BGR
  EXPECT_THROW(runner.run(cv::Mat()), std::invalid_argument);
  runner.run(cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(0)));
  EXPECT_THROW(runner.run(cv::Mat(9, 8, CV_8UC3, cv::Scalar::all(0))), std::invalid_argument);
  EXPECT_EQ(runner.frames(), 1);
}

// The built-in panorama graph (the panoramic sensor's reader): its value_blobs node's table equals
// the kernel's on each frame, whatever the thread count and frames in flight, and one at a time.
namespace {

std::vector<cv::Mat> disc_label_frames(int count, cv::Size size, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> frames;
  for (int f = 0; f < count; ++f) {
    cv::Mat m(size, CV_16SC1, cv::Scalar(0));
    for (int i = 0; i < 60; ++i) {
      cv::circle(m, {rng.uniform(0, size.width), size.height / 2}, rng.uniform(1, size.height / 2),
                 cv::Scalar(rng.uniform(1, 500)), cv::FILLED, cv::LINE_8);
    }
    frames.push_back(m);
  }
  return frames;
}

}  // namespace

TEST(PanoramaGraph, ValueBlobsNodeEqualsTheKernelForEveryThreadCount) {
  const auto frames = disc_label_frames(5, {3600, 320}, 20);
  const auto reference =
      expect_deterministic([] { return pl::compile(pl::panorama_graph(), pl::standard_kernels()); }, frames);
  ASSERT_EQ(reference.size(), frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    const auto& table = std::get<pl::BlobList>(reference[f].outputs.at(0));
    expect_same_blobs(table, kn::extract_value_blobs(frames[f], kn::Connectivity::eight), "frame " + std::to_string(f));
    EXPECT_GT(table.size(), 10U);
  }
}

TEST(PanoramaGraph, TakesS16FramesOnly) {
  pl::InlineRunner runner(pl::compile(pl::panorama_graph(), pl::standard_kernels()));
  EXPECT_EQ(runner.graph().source_type(), pl::PortType::s16);
  EXPECT_THROW(runner.run(cv::Mat(8, 8, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
  const cv::Mat one = (cv::Mat_<std::int16_t>(2, 3) << 0, 4, 4, 0, 0, 9);
  const auto& table = std::get<pl::BlobList>(runner.run(one).at(0));
  ASSERT_EQ(table.size(), 2U);
  EXPECT_EQ(table[0].value, 4);
  EXPECT_EQ(table[1].value, 9);
}
